#pragma once
/// \file thermal_config.h
/// YAML for the thermal model (docs/thermal.md): `site`, `weather`, `thermal` options, thermal
/// `materials` (layers, optics, back boundary) and `objects` (material + facet orientation). The
/// same parsers read these entries inside a scene file and in a standalone thermal file for `tirpol
/// therm`.
///
/// Every object of a standalone thermal scene simulated to one time (`tirpol therm`,
/// docs/thermal.md): the surface temperatures and heat-balance terms at that time, optionally the
/// 24 hours before it, and their formats: the CSV table, the JSON report and the 24-hour plot.

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/core/config.h"
#include "tirpol/thermal/surface_temperature.h"

namespace tirpol::thermal {

/// `site: {name, latitude_deg, longitude_deg, utc_offset_h, elevation_m}`.
Site parse_site(const ConfigNode& node);

/// `weather: {file, year?}` (or just the file name): an .epw or a field-log .csv (which needs
/// `site`). With an EPW and a `site`, the site given in YAML wins (a warning-free override for a
/// nearby scene).
std::shared_ptr<const WeatherSeries> load_weather(const ConfigNode& node,
                                                  const std::optional<Site>& site);

/// `thermal: {spin_up_hours, time_step_s, crank_nicolson, sky_model, use_measured_sky_ir,
/// convection, convection_w_m2_k, ground_albedo, max_cell_thickness_m, delta_t_s}`, all optional.
ThermalOptions parse_thermal_options(const ConfigNode& node);

/// `{name, solar_absorptivity, thermal_emissivity, layers: [{thickness_m, conductivity_w_m_k,
/// density_kg_m3, specific_heat_j_kg_k, cells?}], back?: {kind: adiabatic|fixed|ground,
/// temperature_c?, depth_m?}}`.
ThermalMaterial parse_thermal_material(const ConfigNode& node);

/// A named facet of a thermal material.
struct ThermalObject {
    std::string name;
    std::size_t material = 0;  ///< index into ThermalScene::materials
    Facet facet;
    double shadow_fraction = 0.0;  ///< constant shadow on the direct sun (0 lit … 1 shadowed)
};

/// Everything `tirpol therm` needs.
struct ThermalScene {
    Site site;
    std::shared_ptr<const WeatherSeries> weather;
    ThermalOptions options;
    std::vector<ThermalMaterial> materials;
    std::vector<ThermalObject> objects;
    std::optional<double> time_s;  ///< `time:` when given
};

/// Reads a standalone thermal YAML file (keys: site, weather, time, thermal, materials, objects).
ThermalScene load_thermal_scene(const std::filesystem::path& path);

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
