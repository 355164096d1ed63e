#pragma once
/// \file stokes_image_header.h
/// The EXR header attributes one module writes and another reads, as typed fields: calibration,
/// simulation and twin write them on the images they produce; report, live and calibration read
/// them back. The attribute names and their on-disk types live only in stokes_image_header.cpp
/// (docs/architecture.md lists them).

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/core/image.h"

namespace tirpol {

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
