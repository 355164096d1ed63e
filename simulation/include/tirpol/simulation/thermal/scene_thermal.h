#pragma once
/// \file scene_thermal.h
/// The thermal model inside a scene file (docs/thermal.md, "Scene files"): `time`, `site`, `weather`,
/// `thermal` options and `thermal_materials`; objects whose `temperature` is `predicted` (thermal
/// material named like the object's material) or `{predicted: NAME}`. The scene loader calls these
/// two hooks; everything else stays in the renderer.

#include "tirpol/core/config.h"
#include "tirpol/simulation/scene.h"

namespace tirpol::simulation {

/// Scene-file keys the thermal model adds to the top level.
inline constexpr const char* kThermalSceneKeys[] = {"time", "site", "weather", "thermal", "thermal_materials"};

/// True if an object's `temperature` node asks for the thermal model.
bool is_predicted_temperature(const ConfigNode& temperature_node);

/// Runs the thermal model for a loaded scene whose file has a `weather` entry: sky (Sky::clear_sky at
/// the air temperature with the 8–14 µm window emissivity of the weather record) and sun (SPA
/// direction, grey transmittance DNI/E₀) from the weather when the file gives no `sky`/`sun`, and the
/// temperature of every `predicted` object — per vertex for meshes (shadows by the scene's ray
/// tracer), as a (u, v) map for analytic spheres. Errors name the file and field.
void apply_scene_thermal(const ConfigNode& root, Scene& scene);

}  // namespace tirpol::simulation
