#pragma once
/// \file microgrid_file.h
/// A microgrid frame file → Stokes image: the file read by core's raster_io (16-bit PNG, 16/32-bit
/// TIFF, or one channel of an EXR), then reduce_microgrid.

#include <filesystem>
#include <optional>
#include <string>

#include "tirpol/calibration/microgrid_stokes.h"

namespace tirpol::calibration {

/// What reduce_microgrid_file made, and how: the Stokes image with the facts a caller reports.
struct MicrogridFileReduction {
    Image stokes;               ///< S0 S1 S2 DoLP AoP (microgrid_stokes.h), attributes as there
    MicrogridPattern pattern;   ///< the pattern used: the given one or the file's
    std::string units;          ///< of S0, S1 and S2: the EXR's `units`, else "counts"
    int unrealizable_pixels{};  ///< projected onto the cone (StokesReductionRecord)
};

/// Reads `input` and reduces it. The pattern is `pattern` when given, else the one an EXR header
/// records (`microgrid_pattern_deg`, MicrogridPattern::write_to); with neither, or when both are
/// there and differ, throws tirpol::Error naming the file. The Stokes units are the EXR's `units`
/// attribute when it has one, else "counts" (a PNG/TIFF holds raw counts). Adds the attributes
/// `source_file` and, for PNG/TIFF, `source_depth_bits`. Throws tirpol::Error naming the file for
/// an unreadable file or a frame demosaic_microgrid refuses.
MicrogridFileReduction reduce_microgrid_file(const std::filesystem::path& input,
                                             const std::optional<MicrogridPattern>& pattern,
                                             MicrogridReductionOptions options,
                                             const std::string& exr_channel = "counts");

}  // namespace tirpol::calibration
