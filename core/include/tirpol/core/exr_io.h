#pragma once
/// \file exr_io.h
/// OpenEXR reading and writing. Every channel is written as 32-bit FLOAT (ZIP compressed);
/// reading converts HALF/UINT channels to float. Writes are atomic (temp file + rename).
///
/// Reading single-channel raw camera images saved by other tools (FLIR/vendor exports): 16-bit PNG,
/// TIFF (16/32-bit integer or 32-bit float) and OpenEXR, into an Image with one channel. 8-bit
/// images are refused: they cannot hold camera counts (a display export or a corrupt header).
///
/// The header attributes one module writes and another reads (units, band, variance degrees of
/// freedom, ...) are typed fields of StokesImageHeader; their on-disk names and types live only in
/// core/src/stokes_image_header.cpp, and a present attribute of the wrong type is an error.

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/core/image.h"

namespace tirpol {

/// Writes `image` to `path` atomically. Throws tirpol::Error naming the file on failure (full disk,
/// permissions, ...); an existing file at `path` is untouched on failure.
void write_exr(const std::filesystem::path& path, const Image& image);

/// Reads an EXR. Throws tirpol::Error naming the file for a missing, truncated or corrupt file.
Image read_exr(const std::filesystem::path& path);

/// Reads `path` by extension: .exr (the channel `exr_channel` must exist), .png, .tif/.tiff (one
/// channel, integer values kept as is, no scaling) into an Image whose single channel is named
/// `channel_name`. Throws tirpol::Error naming the file for an unreadable file, a colour or 8-bit
/// image, a declared size beyond limits.h (checked before decoding a PNG) or an unsupported
/// extension.
Image read_raw_image(const std::filesystem::path& path, const std::string& channel_name = "counts",
                     const std::string& exr_channel = "counts");

// ---- The typed header attributes modules exchange ----
/// The radiometric calibration's blackbody range and the fraction of pixels outside it.
struct CalibrationRangeAttribute {
    std::array<double, 2> range_k{};  ///< coldest and hottest calibration blackbody, K
    double outside_fraction = 0.0;    ///< fraction of pixels outside that range, [0, 1]
};

/// Every field is absent (nullopt) when the image does not carry the attribute. (The `{}`
/// initializers let a writer name only its fields, `{.units = "K"}`, without -Wextra warnings.)
struct StokesImageHeader {
    std::optional<std::string> units{};              ///< units of the signal channels
    std::optional<std::array<double, 2>> band_um{};  ///< spectral band [lo, hi], 0 < lo < hi
    /// Degrees of freedom of the *_var channels (the renderer's replicates − 1).
    std::optional<int> variance_dof{};
    std::optional<std::string> variance_note{};  ///< what else the *_var channels hold
    std::optional<std::string> std_includes{};   ///< what the *_std channels hold
    std::optional<CalibrationRangeAttribute> calibration_range{};
    std::optional<std::vector<double>> analyzer_angles_deg{};  ///< nominal analyzer angles
    std::optional<double> fpa_temperature_k{};  ///< focal-plane temperature of a raw frame, K
    /// The lens a render went through (OpenCV pixel convention): fx fy cx cy, pixels.
    std::optional<std::array<double, 4>> camera_intrinsics_px{};
    std::optional<std::vector<double>> camera_distortion{};  ///< OpenCV order k1 k2 p1 p2 k3 ...
};

/// The header of `image`. Throws tirpol::Error naming `where` (the image or its file) and the
/// attribute when one is present with the wrong type or shape.
StokesImageHeader read_stokes_image_header(const Image& image, const std::string& where);
/// Writes the present fields of `header` into `image`'s attributes; absent ones are left as they
/// are.
void write_stokes_image_header(Image& image, const StokesImageHeader& header);

}  // namespace tirpol
