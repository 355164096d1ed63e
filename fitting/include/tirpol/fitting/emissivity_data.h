#pragma once
/// \file emissivity_data.h
/// Measured polarized directional emissivity ε_S0(θ), ε_S1(θ) with uncertainties: the input of the
/// fits (paper §3.2, Fig. 1). The CSV is the one `tirpol extract-emissivity` writes
/// (calibration/emissivity_extraction.h), header
///   name,view_angle_deg,temperature_k,pixels,l_dw_w_m2_sr,l_bb_w_m2_sr,eps_s0,eps_s0_2sigma,eps_s1,
///   eps_s1_2sigma,eps_s2,eps_s2_2sigma
/// of which the fit reads view_angle_deg, eps_s0, eps_s0_2sigma, eps_s1, eps_s1_2sigma (the 2σ columns
/// are halved to standard uncertainties) and, when present, name and wavelength_um. Also accepted: a
/// hand-written CSV angle_deg,e_s0,e_s0_sigma,e_s1,e_s1_sigma[,wavelength_um][,name] with 1σ columns
/// (docs/fitting.md). ε_S1 is in the s/p frame of the plane of emission (pbrdf.h): S1 < 0 means
/// polarized in the plane of emission, as for a horizontal panel in the camera frame.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tirpol::fitting {

/// One measured view angle.
struct EmissivitySample {
    double angle_deg = 0.0;   ///< emission (view) angle from the surface normal, [0°, 90°]
    double e_s0 = 0.0;        ///< ε_S0 = 1 − DHR
    double e_s0_sigma = 0.0;  ///< standard (1σ) uncertainty of e_s0, > 0
    double e_s1 = 0.0;        ///< ε_S1 (plane-of-emission frame, < 0 for emission polarized in that plane)
    double e_s1_sigma = 0.0;  ///< standard (1σ) uncertainty of e_s1, > 0
    std::string name;         ///< target/ROI name from the CSV (may be empty)
};

/// Samples measured in one band (effective wavelength) from one source.
struct EmissivityDataset {
    std::string source;            ///< file (or description) the samples came from, for messages and provenance
    double wavelength_um = 10.0;   ///< effective wavelength at which the model's n + ik is evaluated
    std::vector<EmissivitySample> samples;
};

/// Reads an emissivity CSV (file comment). Rows with a `wavelength_um` column value go to one dataset
/// per distinct wavelength; without that column every row goes to one dataset at
/// `default_wavelength_um`. Lines starting with '#' and blank lines are skipped. Throws tirpol::Error
/// naming file, line and column for a missing column, a non-number, and every check of
/// `validate_dataset`.
std::vector<EmissivityDataset> load_emissivity_csv(const std::filesystem::path& path,
                                                   double default_wavelength_um = 10.0);

/// Checks one dataset: at least one sample; finite values; angles in [0°, 90°]; e_s0 in [0, 1] and
/// e_s1 in [-1, 1] within limits::kEmissivityTolerance (measurement noise); uncertainties finite
/// and > 0; wavelength finite and > 0. Throws tirpol::Error naming `dataset.source` and the sample.
void validate_dataset(const EmissivityDataset& dataset);

/// Writes samples as the calibration CSV layout (name,view_angle_deg,...; unknown columns left empty,
/// 2σ columns = 2 × sigma) plus a wavelength_um column, so that load_emissivity_csv reads them back.
std::string emissivity_csv(const std::vector<EmissivityDataset>& datasets);

}  // namespace tirpol::fitting
