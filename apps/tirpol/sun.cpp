// `tirpol sun`: solar zenith, azimuth and incidence on a tilted surface (NREL SPA).

#include "cli.h"
#include "common_options.h"
#include "tirpol/thermal/solar_position.h"

namespace tirpol::cli {

namespace {
void register_sun(CLI::App& app) {
    auto q = std::make_shared<thermal::SunQuery>();
    auto json = std::make_shared<bool>(false);
    auto& spa = q->spa;
    auto* cmd = app.add_subcommand(
        "sun", "Solar zenith, azimuth and incidence on a tilted surface (NREL SPA)");
    cmd->add_option("--lat", spa.latitude_deg, "Latitude, degrees north")
        ->required()
        ->check(CLI::Range(-90.0, 90.0));
    cmd->add_option("--lon", spa.longitude_deg, "Longitude, degrees east (west negative)")
        ->required()
        ->check(CLI::Range(-180.0, 180.0));
    cmd->add_option(
           "--time", q->time,
           "Time, ISO 8601 with its offset: 2003-10-17T12:30:30-07:00, or Z for UTC (without one, "
           "--utc-offset-h is required)")
        ->required();
    cmd->add_option("--utc-offset-h", q->utc_offset_h,
                    "UTC offset, hours, of a --time written without one");
    cmd->add_option("--elevation-m", spa.elevation_m, "Elevation above sea level, m")
        ->capture_default_str();
    cmd->add_option("--pressure-mbar", spa.pressure_mbar, "Mean local pressure (refraction), mbar")
        ->capture_default_str();
    cmd->add_option("--temperature-c", spa.temperature_c, "Mean local temperature (refraction), °C")
        ->capture_default_str();
    cmd->add_option("--delta-t-s", spa.delta_t_s, "ΔT = TT − UT, seconds")->capture_default_str();
    cmd->add_option("--tilt-deg", q->tilt_deg, "Surface tilt from horizontal, degrees")
        ->check(CLI::Range(0.0, 180.0))
        ->capture_default_str();
    cmd->add_option("--surface-azimuth-deg", q->surface_azimuth_deg,
                    "Azimuth the surface faces, from north eastward")
        ->check(CLI::Range(0.0, 360.0))
        ->capture_default_str();
    add_json_flag(cmd, *json, "Print JSON (keys in docs/thermal.md)");
    cmd->callback([q, json] {
        const thermal::SunReport r = thermal::sun_report(*q);
        *json ? print_json(thermal::sun_report_json(r)) : print_text(thermal::sun_report_text(r));
    });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(320, register_sun);

}  // namespace tirpol::cli
