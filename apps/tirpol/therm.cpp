// `tirpol therm`: surface temperatures of a thermal model's objects at a time, a CSV of them, and a
// 24-hour plot of every object's surface temperature (drawn with OpenCV).

#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/config.h"
#include "tirpol/core/error.h"
#include "tirpol/core/radiometry.h"
#include "tirpol/core/utf8.h"
#include "tirpol/simulation/scene.h"
#include "tirpol/simulation/scene_thermal.h"
#include "tirpol/thermal/civil_time.h"
#include "tirpol/thermal/thermal_config.h"
#include "tirpol/thermal/thermal_run.h"

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
    const thermal::ThermalRun run = thermal::simulate_thermal_scene(scene, at, plot);
    const nlohmann::json out = thermal::thermal_run_json(scene, run);
    if (!a.json) {
        std::printf("%s at %s (%s)\n%-22s %-14s %8s %8s %9s %9s\n", a.file.c_str(),
                    out["time"].get<std::string>().c_str(), scene.site.name.c_str(), "object",
                    "material", "T (K)", "T (°C)", "air (°C)", "solar W/m²");
        for (const auto& r : run.objects) {
            const auto& s = r.samples.back();
            std::printf("%-22s %-14s %8.2f %8.2f %9.2f %9.1f\n", r.object->name.c_str(),
                        scene.materials[r.object->material].name.c_str(), s.surface_temperature_k,
                        s.surface_temperature_k - kZeroCelsiusK,
                        s.air_temperature_k - kZeroCelsiusK, s.fluxes.absorbed_shortwave);
        }
    }
    if (!a.csv.empty()) write_file_atomic(a.csv, thermal::thermal_run_csv(scene, run));
    if (plot) thermal::write_thermal_history_plot(a.plot, scene, run);
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
