#pragma once
/// \file thermal_config.h
/// YAML for the thermal model (docs/thermal.md): `site`, `weather`, `thermal` options, thermal
/// `materials` (layers, optics, back boundary) and `objects` (material + facet orientation). The
/// same parsers read these entries inside a scene file and in a standalone thermal file for `tirpol
/// therm`.

#include <filesystem>
#include <memory>
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

}  // namespace tirpol::thermal
