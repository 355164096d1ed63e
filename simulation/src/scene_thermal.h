#pragma once
/// \file scene_thermal.h
/// The thermal model inside a scene file (docs/thermal.md, "Scene files"): `time`, `site`,
/// `weather`, `thermal` options and `thermal_materials`; objects whose `temperature` is `predicted`
/// (thermal material named like the object's material) or `{predicted: NAME}`. The scene loader
/// calls these two hooks; everything else stays in the renderer.

#include <filesystem>
#include <vector>

#include "tirpol/core/config.h"
#include "tirpol/simulation/scene.h"

namespace tirpol::simulation {

/// Scene-file keys the thermal model adds to the top level.
inline constexpr const char* kThermalSceneKeys[] = {"time", "site", "weather", "thermal",
                                                    "thermal_materials"};

/// True if an object's `temperature` node asks for the thermal model.
bool is_predicted_temperature(const ConfigNode& temperature_node);

/// Runs the thermal model for a loaded scene whose file has a `weather` entry: sky (Sky::clear_sky
/// at the air temperature with the 8–14 µm window emissivity of the weather record) and sun (SPA
/// direction, grey transmittance DNI/E₀) from the weather when the file gives no `sky`/`sun`, and
/// the temperature of every `predicted` object — per vertex for meshes (shadows by the scene's ray
/// tracer), as a (u, v) map for analytic spheres. Errors name the file and field.
void apply_scene_thermal(const ConfigNode& root, Scene& scene);

/// Predicted temperatures of one object: per mesh vertex (`vertex_k`), or a (u, v) map for an
/// analytic sphere (`map_k`, `width` × `height`, row-major, v = 0 the top row).
struct PredictedTemperatures {
    std::size_t object = 0;
    std::vector<double> vertex_k;
    std::vector<float> map_k;
    int width = 0, height = 0;
};

/// Runs the thermal model for every `predicted` object of a loaded scene (geometry and shadows from
/// `scene.tracer`), at the scene file's `time`.
std::vector<PredictedTemperatures> predict_scene_temperatures(const ConfigNode& root,
                                                              const Scene& scene);

/// Writes the predicted temperatures in the forms the scene format imports, so other tools' values
/// can replace them and these can be reused: `<dir>/<object>.csv` with x, y, z in the object's own
/// coordinates (before its `transform`, as `{vertex_csv: FILE}` reads them) and temperature_k for
/// meshes;
/// `<dir>/<object>.exr` with channel `temperature_k` (as `{texture: FILE}` reads it) for spheres.
/// Returns the files written.
std::vector<std::filesystem::path> export_scene_temperatures(const ConfigNode& root,
                                                             const Scene& scene,
                                                             const std::filesystem::path& dir);

}  // namespace tirpol::simulation
