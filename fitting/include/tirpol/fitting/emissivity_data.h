#pragma once
/// \file emissivity_data.h
/// Measured polarized directional emissivity ε_S0(θ), ε_S1(θ) with standard (1σ) uncertainties: the
/// input of the fits (paper §3.2, Fig. 1), read from the emissivity CSV whose schema core owns
/// (tirpol/core/emissivity_csv.h; `tirpol extract-emissivity` writes it). The fit uses
/// view_angle_deg, eps_s0, eps_s0_std, eps_s1, eps_s1_std and, when present, name and
/// wavelength_um. ε_S1 is in the s/p frame of the plane of emission (pbrdf.h): S1 < 0 means
/// polarized in the plane of emission. Rows in the `image` frame are taken as that frame, which
/// they equal when the plane of emission is vertical in the image (a horizontal panel viewed
/// obliquely, docs/fitting.md).

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tirpol::fitting {

/// One measured view angle.
struct EmissivitySample {
    double angle_deg = 0.0;   ///< emission (view) angle from the surface normal, [0°, 90°]
    double eps_s0 = 0.0;      ///< ε_S0 = 1 − DHR
    double eps_s0_std = 0.0;  ///< standard (1σ) uncertainty of eps_s0, > 0
    double eps_s1 =
        0.0;  ///< ε_S1 (plane-of-emission frame, < 0 for emission polarized in that plane)
    double eps_s1_std = 0.0;  ///< standard (1σ) uncertainty of eps_s1, > 0
    std::string name;         ///< target/ROI name from the CSV (may be empty)
};

/// Samples measured in one band (effective wavelength) from one source.
struct EmissivityDataset {
    std::string
        source;  ///< file (or description) the samples came from, for messages and provenance
    double wavelength_um = 10.0;  ///< effective wavelength at which the model's n + ik is evaluated
    std::vector<EmissivitySample> samples;
};

/// Reads an emissivity CSV (file comment). Rows with a `wavelength_um` column value go to one
/// dataset per distinct wavelength; without that column every row goes to one dataset at
/// `default_wavelength_um`. Lines starting with '#' and blank lines are skipped. Throws
/// tirpol::Error naming file, line and column for a missing column, a non-number, and every check
/// of `validate_dataset`.
std::vector<EmissivityDataset> load_emissivity_csv(const std::filesystem::path& path,
                                                   double default_wavelength_um = 10.0);

/// Checks one dataset: at least one sample; finite values; angles in [0°, 90°]; eps_s0 in [0, 1]
/// and eps_s1 in [-1, 1] within limits::kEmissivityTolerance (measurement noise); uncertainties
/// finite and > 0; wavelength finite and > 0. Throws tirpol::Error naming `dataset.source` and the
/// sample.
void validate_dataset(const EmissivityDataset& dataset);

/// Writes samples as an emissivity CSV (core/emissivity_csv.h) in the plane-of-emission frame, with
/// their wavelength_um and unknown columns empty, so that load_emissivity_csv reads them back
/// exactly.
std::string emissivity_csv(const std::vector<EmissivityDataset>& datasets);

}  // namespace tirpol::fitting
