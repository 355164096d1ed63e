// `tirpol therm`: surface temperatures of a thermal model's objects at a time, a CSV of them, and a
// 24-hour plot of every object's surface temperature (drawn with OpenCV).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/config.h"
#include "tirpol/core/error.h"
#include "tirpol/core/line_plot.h"
#include "tirpol/core/radiometry.h"
#include "tirpol/core/utf8.h"
#include "tirpol/simulation/scene.h"
#include "tirpol/simulation/scene_thermal.h"
#include "tirpol/thermal/civil_time.h"
#include "tirpol/thermal/thermal_config.h"

namespace tirpol::cli {

namespace {

struct ThermArgs {
    std::string file;
    std::string at;
    std::string csv;
    std::string plot;
    std::string export_dir;
    bool json = false;
    bool force = false;
};

struct ObjectResult {
    const thermal::ThermalObject* object;
    std::vector<thermal::TemperatureSample>
        history;  // last 24 h when plotting, else only the final sample
};

void draw_plot(const std::string& path, const std::vector<ObjectResult>& results,
               const thermal::ThermalScene& scene, double end_s) {
    static const std::array<std::uint8_t, 3> kPalette[] = {
        {31, 119, 180}, {255, 127, 14},  {44, 160, 44},  {214, 39, 40}, {148, 103, 189},
        {140, 86, 75},  {227, 119, 194}, {188, 189, 34}, {23, 190, 207}};
    std::vector<PlotSeries> series;
    if (!results.empty()) {
        PlotSeries air{"air", {}, {}, {120, 120, 120}, false, true};
        for (const auto& s : results.front().history) {
            air.x.push_back((s.time_s - end_s) / 3600.0);
            air.y.push_back(s.air_temperature_k - kZeroCelsiusK);
        }
        series.push_back(std::move(air));
    }
    for (std::size_t k = 0; k < results.size(); ++k) {
        const auto& obj = *results[k].object;
        PlotSeries line{obj.name + " (" + scene.materials[obj.material].name + ")",
                        {},
                        {},
                        kPalette[k % std::size(kPalette)]};
        for (const auto& s : results[k].history) {
            line.x.push_back((s.time_s - end_s) / 3600.0);
            line.y.push_back(s.surface_temperature_k - kZeroCelsiusK);
        }
        series.push_back(std::move(line));
    }
    LinePlotOptions options;
    options.title =
        "Surface temperature, 24 h to " + thermal::format_time(end_s, scene.site.utc_offset_h);
    options.x_label = "hours before that time";
    options.y_label = "temperature (deg C)";
    options.x_min = -24.0;
    options.x_max = 0.0;
    // Head-room above the data for the legend.
    double lo = 1e300, hi = -1e300;
    for (const auto& line : series)
        for (double y : line.y) lo = std::min(lo, y), hi = std::max(hi, y);
    options.y_min = lo - 0.05 * (hi - lo + 1.0);
    options.y_max = hi + (0.12 + 0.05 * static_cast<double>(series.size())) * (hi - lo + 1.0);
    options.width = 1100;
    options.height = 650;
    write_line_plot(path, series, options);
}

// A scene file (it has a camera): load it — predicted temperatures are computed by the loader at
// the scene's `time` — and report every object's temperature range.
void run_therm_on_scene(const ThermArgs& a) {
    if (!a.at.empty())
        fail(
            "--at: a scene file carries its own `time`; edit the scene (or use a standalone "
            "thermal file)");
    if (!a.plot.empty())
        fail(
            "--plot needs a standalone thermal file (docs/thermal.md); scene files give one "
            "instant");
    const simulation::Scene scene = simulation::load_scene(a.file);
    std::ostringstream csv;
    csv << "object,material,min_temperature_k,max_temperature_k\n";
    nlohmann::json out;
    out["objects"] = nlohmann::json::array();
    if (!a.json) std::printf("%-22s %-26s %10s %10s\n", "object", "material", "min (K)", "max (K)");
    for (const auto& obj : scene.objects) {
        const std::string& mat = scene.materials[obj.material].name;
        if (!a.json)
            std::printf("%-22s %-26s %10.2f %10.2f\n", obj.name.c_str(), mat.c_str(),
                        obj.temperature.min_k(), obj.temperature.max_k());
        csv << obj.name << ',' << mat << ',' << obj.temperature.min_k() << ','
            << obj.temperature.max_k() << '\n';
        out["objects"].push_back({{"name", obj.name},
                                  {"material", mat},
                                  {"min_temperature_k", obj.temperature.min_k()},
                                  {"max_temperature_k", obj.temperature.max_k()}});
    }
    if (!a.csv.empty()) write_file_atomic(a.csv, csv.str());
    if (!a.export_dir.empty()) {
        for (const auto& f : simulation::export_scene_temperatures(ConfigNode::load_file(a.file),
                                                                   scene, a.export_dir))
            if (!a.json) std::printf("wrote %s\n", f.c_str());
    }
    if (a.json) std::printf("%s\n", json_text(out, 2).c_str());
}

void run_therm(const ThermArgs& a) {
    OutputGuard()
        .input(a.file, "FILE")
        .output_file(a.csv, "--csv")
        .output_file(a.plot, "--plot")
        .output_folder(a.export_dir, "--export-dir", {"*.csv", "*.exr"})
        .check(a.force);
    if (ConfigNode::load_file(a.file).has("camera")) return run_therm_on_scene(a);
    if (!a.export_dir.empty()) fail("--export-dir needs a scene file with predicted temperatures");
    const thermal::ThermalScene scene = thermal::load_thermal_scene(a.file);
    double at = 0.0;
    if (!a.at.empty()) {
        at = parse_option_value(
            "--at", [&] { return thermal::parse_time(a.at, scene.site.utc_offset_h, "--at"); });
    } else if (scene.time_s) {
        at = *scene.time_s;
    } else {
        fail("{}: no `time:` entry; give the time with --at", a.file);
    }
    const bool plot = !a.plot.empty();
    const double history_s = plot ? 24 * 3600.0 : 0.0;
    const double start = at - history_s - scene.options.spin_up_hours * 3600.0;
    std::vector<ObjectResult> results;
    for (const auto& obj : scene.objects) {
        const double shadow = obj.shadow_fraction;
        const thermal::ShadowFunction shadow_fn = [shadow](double, const Vec3&) { return shadow; };
        auto history = thermal::simulate_facet(
            *scene.weather, scene.materials[obj.material], obj.facet, start, at, at - history_s,
            plot ? 900.0 : scene.options.time_step_s, scene.options, shadow_fn);
        results.push_back({&obj, std::move(history)});
    }
    std::ostringstream csv;
    csv << "object,material,tilt_deg,azimuth_deg,shadow_fraction,temperature_k,temperature_c,air_"
           "temperature_c,"
           "absorbed_solar_w_m2,absorbed_longwave_w_m2,emitted_longwave_w_m2,convection_w_m2\n";
    nlohmann::json out;
    out["time"] = thermal::format_time(at, scene.site.utc_offset_h);
    out["site"] = {{"name", scene.site.name},
                   {"latitude_deg", scene.site.latitude_deg},
                   {"longitude_deg", scene.site.longitude_deg},
                   {"utc_offset_h", scene.site.utc_offset_h}};
    out["objects"] = nlohmann::json::array();
    if (!a.json)
        std::printf("%s at %s (%s)\n%-22s %-14s %8s %8s %9s %9s\n", a.file.c_str(),
                    out["time"].get<std::string>().c_str(), scene.site.name.c_str(), "object",
                    "material", "T (K)", "T (°C)", "air (°C)", "solar W/m²");
    for (const auto& r : results) {
        const auto& s = r.history.back();
        const auto& obj = *r.object;
        const std::string& mat = scene.materials[obj.material].name;
        const double tc = s.surface_temperature_k - kZeroCelsiusK,
                     air_c = s.air_temperature_k - kZeroCelsiusK;
        if (!a.json)
            std::printf("%-22s %-14s %8.2f %8.2f %9.2f %9.1f\n", obj.name.c_str(), mat.c_str(),
                        s.surface_temperature_k, tc, air_c, s.fluxes.absorbed_shortwave);
        csv << obj.name << ',' << mat << ',' << obj.facet.tilt_deg << ',' << obj.facet.azimuth_deg
            << ',' << obj.shadow_fraction << ',' << s.surface_temperature_k << ',' << tc << ','
            << air_c << ',' << s.fluxes.absorbed_shortwave << ',' << s.fluxes.absorbed_longwave
            << ',' << s.fluxes.emitted_longwave << ',' << s.fluxes.convection << '\n';
        out["objects"].push_back({{"name", obj.name},
                                  {"material", mat},
                                  {"temperature_k", s.surface_temperature_k},
                                  {"air_temperature_k", s.air_temperature_k}});
    }
    if (!a.csv.empty()) write_file_atomic(a.csv, csv.str());
    if (plot) draw_plot(a.plot, results, scene, at);
    if (a.json) std::printf("%s\n", json_text(out, 2).c_str());
}

void register_therm(CLI::App& app) {
    auto args = std::make_shared<ThermArgs>();
    auto* cmd = app.add_subcommand(
        "therm", "Surface temperatures from weather (1D slab model) and a 24-hour plot");
    cmd->add_option(
           "file", args->file,
           "Scene YAML with predicted temperatures, or a standalone thermal YAML (docs/thermal.md)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option(
        "--at", args->at,
        "Time, ISO 8601 (no offset: the site's standard time); default: the file's `time`");
    cmd->add_option("--csv", args->csv,
                    "Write each object's temperature and surface balance to this CSV");
    cmd->add_option("--plot", args->plot, "Write a 24-hour surface-temperature plot (PNG)");
    cmd->add_option("--export-dir", args->export_dir,
                    "Scene files: write predicted temperatures as <object>.csv (vertex_csv) / "
                    "<object>.exr (texture)");
    cmd->add_flag("--json", args->json, "Print JSON (keys in docs/thermal.md)");
    add_force_flag(cmd, args->force);
    cmd->callback([args] { run_therm(*args); });
}

}  // namespace

TIRPOL_REGISTER_COMMAND(310, register_therm);

}  // namespace tirpol::cli
