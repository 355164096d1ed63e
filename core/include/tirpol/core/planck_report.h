#pragma once
/// \file planck_report.h
/// `tirpol planck`: a blackbody's band radiance and dL/dT at a temperature, or the brightness
/// temperature of a band radiance, and the two formats of the answer (JSON, text).

#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "tirpol/core/radiometry.h"

namespace tirpol {

/// The question: one of temperature_k or radiance_w_m2_sr, in the band band_um (with the RSR file
/// named by rsr, empty for a flat response).
struct PlanckQuery {
    std::array<double, 2> band_um{};
    std::string rsr;  ///< the RSR CSV as given, reported back; "" = none
    std::optional<double> temperature_k;
    std::optional<double> radiance_w_m2_sr;
};

/// The answer of evaluate_planck: radiance and its derivative for a temperature, or the brightness
/// temperature for a radiance.
struct PlanckAnswer {
    PlanckQuery query;
    double radiance_w_m2_sr = 0.0;
    std::optional<double> radiance_dT_w_m2_sr_k;     ///< for a temperature
    std::optional<double> brightness_temperature_k;  ///< for a radiance
};

/// Evaluates `query` with `band` (built from query.band_um and the RSR). Throws
/// tirpol::OptionValueError naming --temperature-k for a temperature outside the physical range or
/// --radiance for a radiance that is not positive, tirpol::Error for a query with neither or both,
/// or a result that is not finite.
PlanckAnswer evaluate_planck(const Band& band, const PlanckQuery& query);

/// `tirpol planck`: evaluates `query` in the band its band_um and rsr (a CSV file, read) make.
/// Throws tirpol::OptionValueError naming --band-um for band limits Band refuses, tirpol::Error for
/// an RSR file that does not read, and what the overload above throws.
PlanckAnswer evaluate_planck(const PlanckQuery& query);

/// The JSON answer (docs/cli.md): band_um, rsr (null when none), temperature_k,
/// radiance_w_m2_sr, radiance_dT_w_m2_sr_k or radiance_w_m2_sr, brightness_temperature_k.
nlohmann::json planck_answer_json(const PlanckAnswer& answer);

/// The text answer, one line per quantity.
std::string planck_answer_text(const PlanckAnswer& answer);

}  // namespace tirpol
