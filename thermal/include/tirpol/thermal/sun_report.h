#pragma once
/// \file sun_report.h
/// `tirpol sun`: the sun's position (solar_position.h) at a time written as text, and its incidence
/// on a tilted surface, with the JSON and text formats.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "tirpol/thermal/solar_position.h"

namespace tirpol::thermal {

/// Where (and the atmosphere) in `spa` (its unix_seconds is ignored), when as ISO 8601 text, and
/// the surface.
struct SunQuery {
    SpaInput spa;
    std::string time;                    ///< with its UTC offset, or with utc_offset_h given
    std::optional<double> utc_offset_h;  ///< for a time written without one
    double tilt_deg = 0.0;
    double surface_azimuth_deg = 180.0;
};

/// The answer of sun_report.
struct SunReport {
    SpaInput spa;  ///< with the instant resolved
    SolarPosition position;
    double tilt_deg = 0.0, surface_azimuth_deg = 0.0;
    double incidence_deg = 0.0;  ///< > 90: the sun is behind the surface
};

/// Resolves the time and runs the SPA. A time that does not parse, or has no offset while
/// utc_offset_h is unset (no site, so no standard time to assume), throws OptionValueError for
/// --time; the SPA's own range checks throw tirpol::Error.
SunReport sun_report(const SunQuery& query);

/// solar_position_json of the report.
nlohmann::json sun_report_json(const SunReport& report);

/// Time, zenith, azimuth, declination and incidence, one per line.
std::string sun_report_text(const SunReport& report);

}  // namespace tirpol::thermal
