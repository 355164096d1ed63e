#pragma once
/// \file thermal_run.h
/// Every object of a standalone thermal scene simulated to one time (`tirpol therm`,
/// docs/thermal.md): the surface temperatures and heat-balance terms at that time, optionally the
/// 24 hours before it, and their formats: the CSV table, the JSON report and the 24-hour plot.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tirpol/thermal/surface_temperature.h"
#include "tirpol/thermal/thermal_config.h"

namespace tirpol::thermal {

/// One object's simulated samples: the last 24 h (every 15 min) when the history was asked for,
/// else only the sample at the end time.
struct ObjectTemperatureHistory {
    const ThermalObject* object = nullptr;  ///< into the scene that was simulated
    std::vector<TemperatureSample> samples;
};

/// The result of simulate_thermal_scene.
struct ThermalRun {
    double end_s = 0.0;  ///< Unix seconds of the last sample
    std::vector<ObjectTemperatureHistory> objects;
};

/// Simulates every object of `scene` from the spin-up (scene.options.spin_up_hours before the
/// record start) to `end_s`, each with its constant shadow fraction. With `with_24h_history` the
/// samples of the last 24 h are kept, every 900 s; else only the final one. Throws tirpol::Error
/// when the weather does not cover the span.
ThermalRun simulate_thermal_scene(const ThermalScene& scene, double end_s, bool with_24h_history);

/// The CSV table of the final samples: object, material, tilt_deg, azimuth_deg, shadow_fraction,
/// temperature_k, temperature_c, air_temperature_c, absorbed_solar_w_m2, absorbed_longwave_w_m2,
/// emitted_longwave_w_m2, convection_w_m2 (one row per object).
std::string thermal_run_csv(const ThermalScene& scene, const ThermalRun& run);

/// The JSON report: time (local, the site's offset), site and objects (name, material,
/// temperature_k, air_temperature_k at the end time).
nlohmann::json thermal_run_json(const ThermalScene& scene, const ThermalRun& run);

/// Draws the 24-hour history (air and every object, °C, hours before the end time) as a PNG.
void write_thermal_history_plot(const std::filesystem::path& path, const ThermalScene& scene,
                                const ThermalRun& run);

}  // namespace tirpol::thermal
