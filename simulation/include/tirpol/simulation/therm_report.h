#pragma once
/// \file therm_report.h
/// `tirpol therm`: surface temperatures of a thermal model's objects at one time. A scene file
/// (it has a camera) is loaded as the renderer loads it, which predicts its objects' temperatures
/// at the scene's time; a standalone thermal file (docs/thermal.md) is simulated to --at or its
/// `time`. The report, the CSV tables, exports and the 24-hour plot, and the JSON and text formats.

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/thermal/thermal_config.h"

namespace tirpol::simulation {

/// The file to read and the outputs to write ("" = none).
struct ThermOptions {
    std::string file;        ///< scene YAML or standalone thermal YAML
    std::string at;          ///< ISO 8601 time (standalone files only); "" = the file's `time`
    std::string csv;         ///< CSV table of the objects
    std::string plot;        ///< 24-hour plot PNG (standalone files only)
    std::string export_dir;  ///< predicted temperatures as <object>.csv/.exr (scene files only)
    bool force = false;      ///< existing outputs may be replaced (OutputGuard)
};

/// A scene object's predicted temperature range.
struct SceneObjectTemperature {
    std::string name, material;
    double min_temperature_k = 0.0, max_temperature_k = 0.0;
};

/// The result of run_therm: scene_objects for a scene file, thermal_scene and run for a
/// standalone thermal file.
struct ThermReport {
    ThermOptions options;
    std::vector<SceneObjectTemperature> scene_objects;
    std::vector<std::filesystem::path> exported;  ///< files written under export_dir
    std::shared_ptr<const thermal::ThermalScene> thermal_scene;
    std::optional<thermal::ThermalRun> run;  ///< points into *thermal_scene
};

/// Checks the outputs against the input (OutputGuard: OutputConflict before any work), reads the
/// file, computes the temperatures and writes the outputs asked for. Throws
/// OptionValueError for an --at that does not parse, tirpol::Error for an option the file kind
/// does not take, a file that does not load or weather that does not cover the time.
ThermReport run_therm(const ThermOptions& options);

/// Scene files: {"objects": [{name, material, min_temperature_k, max_temperature_k}]}; standalone
/// files: thermal_run_json.
nlohmann::json therm_report_json(const ThermReport& report);

/// The table of objects (and the exported files) as text.
std::string therm_report_text(const ThermReport& report);

}  // namespace tirpol::simulation
