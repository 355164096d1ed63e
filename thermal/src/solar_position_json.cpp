#include <nlohmann/json.hpp>

#include "tirpol/thermal/civil_time.h"
#include "tirpol/thermal/solar_position.h"

namespace tirpol::thermal {

nlohmann::json solar_position_json(const SpaInput& input, const SolarPosition& position,
                                   double tilt_deg, double surface_azimuth_deg) {
    nlohmann::json out;
    out["time_utc"] = format_time(input.unix_seconds, 0.0);
    out["julian_day"] = position.julian_day;
    out["zenith_deg"] = position.zenith_deg;
    out["elevation_deg"] = position.elevation_deg;
    out["azimuth_deg"] = position.azimuth_deg;
    out["declination_deg"] = position.declination_deg;
    out["hour_angle_deg"] = position.hour_angle_deg;
    out["earth_sun_distance_au"] = position.earth_radius_au;
    out["surface"] = {
        {"tilt_deg", tilt_deg},
        {"azimuth_deg", surface_azimuth_deg},
        {"incidence_deg", incidence_angle_deg(position, tilt_deg, surface_azimuth_deg)}};
    return out;
}

}  // namespace tirpol::thermal
