#pragma once
/// \file frame_stack_io.h
/// Frame stacks for `tirpol noise` from the files cameras and other tools write, and the same stack
/// in kelvin after a radiometric calibration (docs/calibration.md, "Noise").

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

#include "tirpol/calibration/noise.h"
#include "tirpol/calibration/radiometric.h"

namespace tirpol::calibration {

/// A headerless raw file of consecutive frames, row-major, little-endian (as pyradi's
/// ryfiles.readRawFrames reads them).
struct RawFrameFormat {
    enum class Type { UInt8, UInt16, Float32 };
    int width = 0, height = 0;
    Type type = Type::UInt16;
    std::size_t header_bytes = 0;  ///< skipped at the start of the file
};

/// Parses "uint8" | "uint16" | "float32"; throws tirpol::Error naming the accepted values.
RawFrameFormat::Type raw_type_from_string(const std::string& text);

/// Loads a stack from: a directory of frames (.exr with channel `counts`, 8/16-bit .png,
/// .tif/.tiff; sorted by name; all the same size), one EXR with channels frame_* (sorted by name),
/// or, when `raw` is given, a raw file whose size must be header_bytes + N·width·height·bytes per
/// value. Throws tirpol::Error naming the path for fewer than 2 frames, mixed sizes, a directory
/// with no frame file (listing the extensions looked for) or a raw file of the wrong size.
FrameStack load_frame_stack(const std::filesystem::path& path,
                            const std::optional<RawFrameFormat>& raw = std::nullopt);

/// The stack in kelvin: each frame through counts_to_radiance (bad pixels replaced by their good
/// neighbours, FPA-dependent calibrations at `fpa_temperature_k`), then to temperature to first
/// order about T₀, the brightness temperature of the stack's mean radiance:
/// T = T₀ + (L − L(T₀))/(dL/dT)(T₀) (for noise-sized deviations the second-order term is
/// ≈ 1e-4 of the deviation). Throws tirpol::Error for a size mismatch.
FrameStack temperature_stack(const FrameStack& counts, const RadiometricCalibration& cal,
                             std::optional<double> fpa_temperature_k = std::nullopt);

}  // namespace tirpol::calibration
