#include <fmt/printf.h>

#include "tirpol/core/limits.h"
#include "tirpol/thermal/civil_time.h"
#include "tirpol/thermal/solar_position.h"

namespace tirpol::thermal {

namespace {
double time_at_offset(const std::string& text, double utc_offset_h) {
    try {
        return parse_time(text, utc_offset_h, "--time");
    } catch (const Error& e) {
        throw OptionValueError("--time", e.what());
    }
}
}  // namespace

SunReport sun_report(const SunQuery& q) {
    // A time written with an offset reads the same whatever default offset it is given.
    const double as_utc = time_at_offset(q.time, 0.0);
    const bool has_offset = as_utc == time_at_offset(q.time, 1.0);
    if (!has_offset && !q.utc_offset_h)
        throw OptionValueError(
            "--time", fmt::format("{} has no UTC offset: write it (2003-10-17T12:30:30-07:00, or "
                                  "Z for UTC) or give --utc-offset-h",
                                  q.time));
    SunReport r;
    r.spa = q.spa;
    r.spa.unix_seconds = has_offset ? as_utc : time_at_offset(q.time, *q.utc_offset_h);
    r.position = solar_position(r.spa);
    r.tilt_deg = q.tilt_deg;
    r.surface_azimuth_deg = q.surface_azimuth_deg;
    r.incidence_deg = incidence_angle_deg(r.position, q.tilt_deg, q.surface_azimuth_deg);
    return r;
}

nlohmann::json sun_report_json(const SunReport& r) {
    return solar_position_json(r.spa, r.position, r.tilt_deg, r.surface_azimuth_deg);
}

std::string sun_report_text(const SunReport& r) {
    const SolarPosition& s = r.position;
    return fmt::sprintf("time (UTC)        %s   JD %.6f\n", format_time(r.spa.unix_seconds, 0.0),
                        s.julian_day) +
           fmt::sprintf("zenith            %10.5f°  (elevation %.5f°, refraction-corrected)\n",
                        s.zenith_deg, s.elevation_deg) +
           fmt::sprintf("azimuth           %10.5f°  (from north, eastward)\n", s.azimuth_deg) +
           fmt::sprintf("declination       %10.5f°   hour angle %.5f°\n", s.declination_deg,
                        s.hour_angle_deg) +
           fmt::sprintf(
               "incidence         %10.5f°  on a surface tilted %.2f° facing azimuth %.2f°%s\n",
               r.incidence_deg, r.tilt_deg, r.surface_azimuth_deg,
               r.incidence_deg >= 90.0 ? " (sun behind the surface)" : "");
}

}  // namespace tirpol::thermal
