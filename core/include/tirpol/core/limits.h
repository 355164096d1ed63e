#pragma once
/// \file limits.h
/// Resource limits and physical ranges that every reader, library function and command-line option
/// checks before it allocates or accepts a value. One table, so that a limit is raised (or
/// explained) once; docs/cli.md lists it for users.

#include <cstddef>
#include <cstdint>

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

/// Largest text input (JSON manifest, YAML config, CSV table) read into memory, bytes. The largest
/// real ones (an hourly EPW year, a 1 M-row spectrum) are ≈ 40 MB; beyond this a file is refused
/// before it is read, and a read never goes further (a device that streams for ever).
inline constexpr std::uintmax_t kMaxTextFileBytes = std::uintmax_t{256} << 20;

/// Largest image file (EXR, PNG, TIFF) opened, bytes: a 16384² float image with four channels is 4
/// GiB uncompressed; the pixel-count limits above bound what is decoded.
inline constexpr std::uintmax_t kMaxImageFileBytes = std::uintmax_t{4} << 30;

/// Physical temperature range accepted for any temperature in a file or on the command line, K.
inline constexpr double kMinTemperatureK = 1.0;
inline constexpr double kMaxTemperatureK = 10000.0;

/// Measured emissivities may stray outside [0, 1] by noise; beyond this tolerance they are errors.
inline constexpr double kEmissivityTolerance = 0.05;
/// Smallest emissivity an emissivity correction divides by (FLIR's object-signal inversion): below
/// it the reflected term dominates and 1/ε amplifies a count of noise into kelvins of error (ε =
/// 0.01 gives 100 counts per count); FLIR's cameras offer the same range (data sheets: "emissivity
/// correction variable from 0.01 to 1.0").
inline constexpr double kMinCorrectionEmissivity = 0.01;

/// Wavelength range of any band or wavelength, µm: 0.1 µm (far UV, below which no thermal source
/// of ≤ 10000 K emits a measurable fraction) to 1000 µm (the end of the far infrared).
inline constexpr double kMinWavelengthUm = 0.1;
inline constexpr double kMaxWavelengthUm = 1000.0;
/// Quadrature nodes of one band (16 per 0.25 µm panel, plus the RSR's knots): the whole
/// 0.1–1000 µm range at the finest panel is ≈ 64 000 nodes; an RSR with a million knots is not.
inline constexpr std::size_t kMaxBandNodes = std::size_t{1} << 20;

/// Samples per pixel of a render (the project's reference renders use ≤ 4096).
inline constexpr int kMaxSamplesPerPixel = 1 << 20;
/// Multi-start count of a fit (each start is a full Ceres solve; 16 is the default, 1000 already
/// takes minutes).
inline constexpr int kMaxFitStarts = 10000;
/// Frames averaged or captured per step and repeats of a plan or command.
inline constexpr int kMaxFramesPerStep = 100000;

/// Fraction of the memory the kernel reports available (MemAvailable) that one job may plan to
/// use: the rest is left to the page cache and the other processes.
inline constexpr double kMaxMemoryFraction = 0.8;

}  // namespace tirpol::limits
