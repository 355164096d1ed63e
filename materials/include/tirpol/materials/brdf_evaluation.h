#pragma once
/// \file brdf_evaluation.h
/// The Mueller BRDF of a material for one incident/exitant pair of directions, as `tirpol brdf`
/// reports it: the evaluation and its two formats (JSON, text).

#include <array>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tirpol/core/mueller.h"
#include "tirpol/materials/pbrdf.h"

namespace tirpol::materials {

/// What to evaluate: a material (file or library name), a wavelength and two directions given as
/// zenith and azimuth in degrees.
struct BrdfEvaluationOptions {
    std::string material;  ///< YAML file or library name (material_file)
    double wavelength_um = 10.0;
    std::array<double, 2> incident_deg{};  ///< zenith [0, 90], azimuth
    std::array<double, 2> exitant_deg{};   ///< zenith [0, 90], azimuth
};

/// The result of evaluate_brdf.
struct BrdfEvaluation {
    std::string material;  ///< the material's name
    std::string model;     ///< its pBRDF model
    double wavelength_um = 0.0;
    std::array<double, 2> incident_deg{}, exitant_deg{};
    MuellerMatrix mueller_brdf_per_sr = MuellerMatrix::Zero();
    std::vector<BrdfParameter> parameters;  ///< at the wavelength
    bool has_delta = false;                 ///< a specular delta lobe outside the finite BRDF
};

/// The unit direction of zenith `theta_deg` and azimuth `phi_deg` in the surface frame (normal +z).
/// Throws tirpol::Error when the zenith is outside [0, 90] or the azimuth is not finite.
Vec3 direction_from_zenith_azimuth_deg(double theta_deg, double phi_deg);

/// Loads the material and evaluates its Mueller BRDF (incident Stokes in surface_frame(-wi, n),
/// exitant in surface_frame(wo, n)). Throws tirpol::Error for a bad direction, a material that
/// does not load, or a wavelength outside the material's data range.
BrdfEvaluation evaluate_brdf(const BrdfEvaluationOptions& options);

/// The JSON report (keys in docs/cli.md): material, model, wavelength_um, incident_deg,
/// exitant_deg, frames, mueller_brdf_per_sr (4 rows), parameters {name: {value, unit}}, has_delta.
nlohmann::json brdf_evaluation_json(const BrdfEvaluation& evaluation);

/// The text report: a heading, the 4×4 matrix, the delta-lobe note and the parameters.
std::string brdf_evaluation_text(const BrdfEvaluation& evaluation);

}  // namespace tirpol::materials
