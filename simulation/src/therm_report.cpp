#include "tirpol/simulation/therm_report.h"

#include <fmt/printf.h>

#include <sstream>

#include "scene_thermal.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/config.h"
#include "tirpol/core/error.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/output_guard.h"
#include "tirpol/core/radiometry.h"
#include "tirpol/simulation/scene.h"
#include "tirpol/thermal/civil_time.h"

namespace tirpol::simulation {

namespace {
// A scene file: loading it predicts the temperatures at the scene's `time`.
void therm_on_scene(ThermReport& report) {
    const ThermOptions& o = report.options;
    if (!o.at.empty())
        fail(
            "--at: a scene file carries its own `time`; edit the scene (or use a standalone "
            "thermal file)");
    if (!o.plot.empty())
        fail(
            "--plot needs a standalone thermal file (docs/thermal.md); scene files give one "
            "instant");
    const Scene scene = load_scene(o.file);
    std::ostringstream csv;
    csv << "object,material,min_temperature_k,max_temperature_k\n";
    for (const auto& obj : scene.objects) {
        const SceneObjectTemperature t{obj.name, scene.materials[obj.material].name,
                                       obj.temperature.min_k(), obj.temperature.max_k()};
        csv << t.name << ',' << t.material << ',' << t.min_temperature_k << ','
            << t.max_temperature_k << '\n';
        report.scene_objects.push_back(t);
    }
    if (!o.csv.empty()) write_file_atomic(o.csv, csv.str());
    if (!o.export_dir.empty())
        report.exported =
            export_scene_temperatures(ConfigNode::load_file(o.file), scene, o.export_dir);
}
}  // namespace

ThermReport run_therm(const ThermOptions& o) {
    OutputGuard()
        .input(o.file, "FILE")
        .output_file(o.csv, "--csv")
        .output_file(o.plot, "--plot")
        .output_folder(o.export_dir, "--export-dir", {"*.csv", "*.exr"})
        .check(o.force);
    ThermReport report;
    report.options = o;
    if (ConfigNode::load_file(o.file).has("camera")) {
        therm_on_scene(report);
        return report;
    }
    if (!o.export_dir.empty()) fail("--export-dir needs a scene file with predicted temperatures");
    auto scene = std::make_shared<const thermal::ThermalScene>(thermal::load_thermal_scene(o.file));
    double at = 0.0;
    if (!o.at.empty()) {
        try {
            at = thermal::parse_time(o.at, scene->site.utc_offset_h, "--at");
        } catch (const Error& e) {
            throw OptionValueError("--at", e.what());
        }
    } else if (scene->time_s) {
        at = *scene->time_s;
    } else {
        fail("{}: no `time:` entry; give the time with --at", o.file);
    }
    report.run = thermal::simulate_thermal_scene(*scene, at, !o.plot.empty());
    report.thermal_scene = scene;
    if (!o.csv.empty()) write_file_atomic(o.csv, thermal::thermal_run_csv(*scene, *report.run));
    if (!o.plot.empty()) thermal::write_thermal_history_plot(o.plot, *scene, *report.run);
    return report;
}

nlohmann::json therm_report_json(const ThermReport& r) {
    if (r.thermal_scene) return thermal::thermal_run_json(*r.thermal_scene, *r.run);
    nlohmann::json out;
    out["objects"] = nlohmann::json::array();
    for (const auto& t : r.scene_objects)
        out["objects"].push_back({{"name", t.name},
                                  {"material", t.material},
                                  {"min_temperature_k", t.min_temperature_k},
                                  {"max_temperature_k", t.max_temperature_k}});
    return out;
}

std::string therm_report_text(const ThermReport& r) {
    if (!r.thermal_scene) {
        std::string text =
            fmt::sprintf("%-22s %-26s %10s %10s\n", "object", "material", "min (K)", "max (K)");
        for (const auto& t : r.scene_objects)
            text += fmt::sprintf("%-22s %-26s %10.2f %10.2f\n", t.name, t.material,
                                 t.min_temperature_k, t.max_temperature_k);
        for (const auto& f : r.exported) text += fmt::sprintf("wrote %s\n", f.string());
        return text;
    }
    const thermal::ThermalScene& scene = *r.thermal_scene;
    // The column heads as printf pads them (by bytes: each "°" takes one column less).
    std::string text =
        fmt::sprintf("%s at %s (%s)\n", r.options.file,
                     thermal::format_time(r.run->end_s, scene.site.utc_offset_h), scene.site.name) +
        "object                 material          T (K)  T (°C) air (°C) solar W/m²\n";
    for (const auto& o : r.run->objects) {
        const auto& s = o.samples.back();
        text += fmt::sprintf("%-22s %-14s %8.2f %8.2f %9.2f %9.1f\n", o.object->name,
                             scene.materials[o.object->material].name, s.surface_temperature_k,
                             s.surface_temperature_k - kZeroCelsiusK,
                             s.air_temperature_k - kZeroCelsiusK, s.fluxes.absorbed_shortwave);
    }
    return text;
}

}  // namespace tirpol::simulation
