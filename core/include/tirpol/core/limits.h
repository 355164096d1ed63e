#pragma once
/// \file limits.h
/// Resource limits and physical ranges that every reader in core checks before it allocates or
/// accepts a value. One place, so that a limit is raised (or explained) once.

#include <cstddef>

namespace tirpol::limits {

/// Largest image side tirpol reads or creates, pixels (thermal cameras are ≤ 1280; renders ≤ 8K).
inline constexpr int kMaxImageSide = 16384;
/// Largest image area, pixels (8192² ≈ 67 M: 268 MB per float channel).
inline constexpr std::size_t kMaxImagePixels = std::size_t{1} << 26;
/// Largest decoded-size-to-file-size ratio accepted for a compressed image. zlib cannot exceed
/// ~1032:1, RLE 64:1; a header declaring more pixels than this is a lie, not an image.
inline constexpr double kMaxCompressionRatio = 4096.0;
/// Data rows accepted in a CSV input (a spectrum, an emissivity table, a weather series).
inline constexpr std::size_t kMaxCsvRows = 1'000'000;

/// Physical temperature range accepted for any temperature in a file or on the command line, K.
inline constexpr double kMinTemperatureK = 1.0;
inline constexpr double kMaxTemperatureK = 10000.0;

/// Measured emissivities may stray outside [0, 1] by noise; beyond this tolerance they are errors.
inline constexpr double kEmissivityTolerance = 0.05;

}  // namespace tirpol::limits
