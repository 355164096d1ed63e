// `tirpol sun`: solar zenith, azimuth and incidence on a tilted surface (NREL SPA).

#include <cstdio>
#include <optional>

#include "cli.h"
#include "tirpol/core/error.h"
#include "tirpol/core/utf8.h"
#include "tirpol/thermal/civil_time.h"
#include "tirpol/thermal/solar_position.h"

namespace tirpol::cli {

namespace {
struct SunArgs {
    double latitude_deg = 0.0, longitude_deg = 0.0;
    std::string time;
    std::optional<double> utc_offset_h;
    double elevation_m = 0.0;
    double pressure_mbar = 1013.25;
    double temperature_c = 15.0;
    double delta_t_s = 69.0;
    double tilt_deg = 0.0;
    double surface_azimuth_deg = 180.0;
    bool json = false;
};

void run_sun(const SunArgs& a) {
    // `sun` knows no site, hence no standard time to assume: a time without an offset needs
    // --utc-offset-h.
    const double as_utc =
        parse_option_value("--time", [&] { return thermal::parse_time(a.time, 0.0, "--time"); });
    const bool has_offset = as_utc == thermal::parse_time(a.time, 1.0, "--time");
    if (!has_offset && !a.utc_offset_h)
        usage_error(
            "--time",
            "{} has no UTC offset: write it (2003-10-17T12:30:30-07:00, or Z for UTC) or give "
            "--utc-offset-h",
            a.time);
    thermal::SpaInput in;
    in.unix_seconds = has_offset ? as_utc : thermal::parse_time(a.time, *a.utc_offset_h, "--time");
    in.latitude_deg = a.latitude_deg;
    in.longitude_deg = a.longitude_deg;
    in.elevation_m = a.elevation_m;
    in.pressure_mbar = a.pressure_mbar;
    in.temperature_c = a.temperature_c;
    in.delta_t_s = a.delta_t_s;
    const thermal::SolarPosition s = thermal::solar_position(in);
    const double incidence = thermal::incidence_angle_deg(s, a.tilt_deg, a.surface_azimuth_deg);
    if (a.json) {
        std::printf(
            "%s\n",
            json_text(thermal::solar_position_json(in, s, a.tilt_deg, a.surface_azimuth_deg), 2)
                .c_str());
        return;
    }
    std::printf("time (UTC)        %s   JD %.6f\n",
                thermal::format_time(in.unix_seconds, 0.0).c_str(), s.julian_day);
    std::printf("zenith            %10.5f°  (elevation %.5f°, refraction-corrected)\n",
                s.zenith_deg, s.elevation_deg);
    std::printf("azimuth           %10.5f°  (from north, eastward)\n", s.azimuth_deg);
    std::printf("declination       %10.5f°   hour angle %.5f°\n", s.declination_deg,
                s.hour_angle_deg);
    std::printf("incidence         %10.5f°  on a surface tilted %.2f° facing azimuth %.2f°%s\n",
                incidence, a.tilt_deg, a.surface_azimuth_deg,
                incidence >= 90.0 ? " (sun behind the surface)" : "");
}

void register_sun(CLI::App& app) {
    auto args = std::make_shared<SunArgs>();
    auto* cmd = app.add_subcommand(
        "sun", "Solar zenith, azimuth and incidence on a tilted surface (NREL SPA)");
    cmd->add_option("--lat", args->latitude_deg, "Latitude, degrees north")
        ->required()
        ->check(CLI::Range(-90.0, 90.0));
    cmd->add_option("--lon", args->longitude_deg, "Longitude, degrees east (west negative)")
        ->required()
        ->check(CLI::Range(-180.0, 180.0));
    cmd->add_option(
           "--time", args->time,
           "Time, ISO 8601 with its offset: 2003-10-17T12:30:30-07:00, or Z for UTC (without one, "
           "--utc-offset-h is required)")
        ->required();
    cmd->add_option("--utc-offset-h", args->utc_offset_h,
                    "UTC offset, hours, of a --time written without one");
    cmd->add_option("--elevation-m", args->elevation_m, "Elevation above sea level, m")
        ->capture_default_str();
    cmd->add_option("--pressure-mbar", args->pressure_mbar,
                    "Mean local pressure (refraction), mbar")
        ->capture_default_str();
    cmd->add_option("--temperature-c", args->temperature_c,
                    "Mean local temperature (refraction), °C")
        ->capture_default_str();
    cmd->add_option("--delta-t-s", args->delta_t_s, "ΔT = TT − UT, seconds")->capture_default_str();
    cmd->add_option("--tilt-deg", args->tilt_deg, "Surface tilt from horizontal, degrees")
        ->check(CLI::Range(0.0, 180.0))
        ->capture_default_str();
    cmd->add_option("--surface-azimuth-deg", args->surface_azimuth_deg,
                    "Azimuth the surface faces, from north eastward")
        ->check(CLI::Range(0.0, 360.0))
        ->capture_default_str();
    cmd->add_flag("--json", args->json, "Print JSON (keys in docs/thermal.md)");
    cmd->callback([args] { run_sun(*args); });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(320, register_sun);

}  // namespace tirpol::cli
