// Example: sun position check and a day of surface temperatures for the ball-on-snow example.

#include <cstdio>
#include <sstream>

#include "examples.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/quicklook.h"
#include "tirpol/core/radiometry.h"
#include "tirpol/core/source_tree.h"
#include "tirpol/thermal/civil_time.h"
#include "tirpol/thermal/solar_position.h"
#include "tirpol/thermal/thermal_config.h"

namespace tirpol::examples {

namespace {

// config/thermal of the source tree, searched upwards from the working directory and the
// executable.
std::filesystem::path find_thermal_config() {
    return find_config("thermal/ball_on_snow_thermal.yaml");
}

}  // namespace

void thermal_example(const std::filesystem::path& out_dir) {
    // The SPA report's worked example (Reda & Andreas, NREL/TP-560-34302): zenith 50.11162°,
    // azimuth 194.34024°.
    thermal::SpaInput in;
    in.unix_seconds = thermal::parse_time("2003-10-17T12:30:30-07:00", 0.0);
    in.latitude_deg = 39.742476;
    in.longitude_deg = -105.1786;
    in.elevation_m = 1830.14;
    in.pressure_mbar = 820.0;
    in.temperature_c = 11.0;
    in.delta_t_s = 67.0;
    const auto sun = thermal::solar_position(in);
    std::printf(
        "  SPA worked example: zenith %.5f° (report 50.11162°), azimuth %.5f° (report "
        "194.34024°)\n",
        sun.zenith_deg, sun.azimuth_deg);

    const thermal::ThermalScene scene = thermal::load_thermal_scene(find_thermal_config());
    const double end = *scene.time_s;
    const double start = end - (24.0 + scene.options.spin_up_hours) * 3600.0;
    std::vector<PlotSeries> series;
    std::ostringstream csv;
    csv << "object,material,temperature_k\n";
    static const std::array<std::uint8_t, 3> kColours[] = {{31, 119, 180},  {255, 127, 14},
                                                           {44, 160, 44},   {214, 39, 40},
                                                           {148, 103, 189}, {140, 86, 75}};
    for (std::size_t k = 0; k < scene.objects.size(); ++k) {
        const auto& obj = scene.objects[k];
        const double shadow = obj.shadow_fraction;
        const auto h = thermal::simulate_facet(
            *scene.weather, scene.materials[obj.material], obj.facet, start, end, end - 24 * 3600.0,
            900.0, scene.options, [shadow](double, const Vec3&) { return shadow; });
        PlotSeries s{
            obj.name + " (" + scene.materials[obj.material].name + ")", {}, {}, kColours[k % 6]};
        for (const auto& x : h) {
            s.x.push_back((x.time_s - end) / 3600.0);
            s.y.push_back(x.surface_temperature_k - kZeroCelsiusK);
        }
        series.push_back(std::move(s));
        csv << obj.name << ',' << scene.materials[obj.material].name << ','
            << h.back().surface_temperature_k << '\n';
        std::printf("  %-20s %-12s %7.2f °C\n", obj.name.c_str(),
                    scene.materials[obj.material].name.c_str(),
                    h.back().surface_temperature_k - kZeroCelsiusK);
    }
    write_file_atomic(out_dir / "thermal" / "ball_on_snow_temperatures.csv", csv.str());
    LinePlotOptions options;
    options.title = "Surface temperature, 24 h to " +
                    thermal::format_time(end, scene.site.utc_offset_h) + " (synthetic weather)";
    options.x_label = "hours before that time";
    options.y_label = "temperature (deg C)";
    options.width = 1100;
    options.height = 650;
    options.legend_y_fraction = 0.0;
    write_line_plot(out_dir / "thermal" / "ball_on_snow_24h.png", series, options);
    std::printf("  table and plot: %s\n", (out_dir / "thermal").c_str());
}

}  // namespace tirpol::examples
