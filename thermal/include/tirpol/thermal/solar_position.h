#pragma once
/// \file solar_position.h
/// The NREL Solar Position Algorithm (SPA): I. Reda and A. Andreas, "Solar Position Algorithm for
/// Solar Radiation Applications", NREL/TP-560-34302 (2003, rev. 2008); Solar Energy 76(5) 577–589
/// (2004). Topocentric zenith and azimuth, uncertainty ±0.0003° for years −2000…6000. Equation
/// numbers below are the report's (section 3).
///
/// `tirpol sun`: the sun's position (solar_position.h) at a time written as text, and its incidence
/// on a tilted surface, with the JSON and text formats.

#include <nlohmann/json.hpp>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>

#include "tirpol/core/geometry.h"

namespace tirpol::thermal {

/// Where and when, and the atmosphere used for the refraction correction.
struct SpaInput {
    double unix_seconds = 0.0;       ///< the instant (UTC); see civil_time.h
    double latitude_deg = 0.0;       ///< geodetic, north positive
    double longitude_deg = 0.0;      ///< east positive (Golden, CO is −105.1786)
    double elevation_m = 0.0;        ///< above mean sea level
    double pressure_mbar = 1013.25;  ///< annual mean local pressure (refraction, eq. 42)
    double temperature_c = 15.0;     ///< annual mean local temperature (refraction, eq. 42)
    double delta_t_s =
        69.0;  ///< ΔT = TT − UT, seconds (≈69 s around 2020; the report's example: 67)
    double delta_ut1_s = 0.0;                    ///< ΔUT1 = UT1 − UTC, seconds (|ΔUT1| < 0.9 s)
    double atmospheric_refraction_deg = 0.5667;  ///< refraction at sunrise/sunset (eq. 42's gate)
};

/// Results; the intermediate values are those the report tabulates for its worked example (Table
/// A5.2).
struct SolarPosition {
    double julian_day = 0.0;                   ///< JD (eq. 4)
    double heliocentric_longitude_deg = 0.0;   ///< L (eq. 9)
    double heliocentric_latitude_deg = 0.0;    ///< B (eq. 11)
    double earth_radius_au = 0.0;              ///< R (eq. 12)
    double nutation_longitude_deg = 0.0;       ///< Δψ (eq. 22)
    double nutation_obliquity_deg = 0.0;       ///< Δε (eq. 23)
    double true_obliquity_deg = 0.0;           ///< ε (eq. 25)
    double right_ascension_deg = 0.0;          ///< geocentric α (eq. 30)
    double declination_deg = 0.0;              ///< geocentric δ (eq. 31)
    double hour_angle_deg = 0.0;               ///< observer local hour angle H (eq. 32)
    double topocentric_declination_deg = 0.0;  ///< δ′ (eq. 39)
    double elevation_deg = 0.0;  ///< topocentric elevation with refraction, e (eq. 43)
    double zenith_deg = 0.0;     ///< topocentric zenith θ = 90° − e (eq. 44)
    double azimuth_deg = 0.0;  ///< topocentric azimuth Φ, from north, eastward, 0–360° (eq. 46)
};

/// Runs the SPA. Throws tirpol::Error for a latitude outside ±90°, a longitude outside ±180°, or a
/// time outside the algorithm's validity (years −2000…6000).
SolarPosition solar_position(const SpaInput& input);

/// Incidence angle (degrees) of the sun on a surface tilted `tilt_deg` from horizontal whose normal
/// points to azimuth `surface_azimuth_deg` (from north, eastward) — the report's eq. 47 with its γ
/// measured from north rather than from south. >90° means the sun is behind the surface.
double incidence_angle_deg(const SolarPosition& sun, double tilt_deg, double surface_azimuth_deg);

/// `tirpol sun --json` (keys in docs/thermal.md): the instant in UTC, Julian day, zenith,
/// elevation, azimuth, declination, hour angle, Earth–Sun distance, and the incidence on the
/// surface tilted `tilt_deg` facing `surface_azimuth_deg`.
nlohmann::json solar_position_json(const SpaInput& input, const SolarPosition& position,
                                   double tilt_deg, double surface_azimuth_deg);

/// Unit vector towards the sun in the world frame (x east, y north, z up).
Vec3 sun_direction(const SolarPosition& sun);

/// Unit outward normal (x east, y north, z up) of a facet with tilt (0 = facing up) and azimuth of
/// its downslope direction (from north, eastward).
Vec3 facet_normal(double tilt_deg, double surface_azimuth_deg);

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
