#pragma once
// Decoding 16-bit grey PNGs (raw camera counts) with libpng directly rather than through OpenCV:
// OpenCV's PNG decoder leaves libpng's default handlers in place, which print "libpng warning:
// iCCP: known incorrect sRGB profile" and the like on stderr for chunks that cannot change a count.

#include <cstdint>
#include <filesystem>
#include <vector>

namespace tirpol::detail {

struct PngCounts {
    int width = 0, height = 0;
    std::vector<std::uint16_t> counts;  ///< row-major, native byte order
};

/// Reads a single-channel 16-bit PNG. libpng's warnings are dropped (they concern ancillary chunks:
/// colour profiles, text, time stamps); its errors and any other layout become tirpol::Error naming
/// the file. Call after the header checks of raster_io.cpp (size limits before allocation).
PngCounts read_png_counts(const std::filesystem::path& path);

}  // namespace tirpol::detail
