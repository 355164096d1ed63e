#pragma once
/// \file scene.h
/// A scene ready to render: geometry in Embree, a material and a temperature field per object, the
/// sky, the sun, the camera, the spectral band and the sampling settings. Loaded from the YAML
/// scene format of docs/scene-format.md.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tirpol/core/config.h"
#include "tirpol/core/radiometry.h"
#include "tirpol/materials/pbrdf.h"
#include "tirpol/simulation/pinhole_camera.h"
#include "tirpol/simulation/ray_tracer.h"
#include "tirpol/simulation/sky.h"
#include "tirpol/simulation/temperature_field.h"

namespace tirpol::simulation {

/// Default and largest allowed `max_bounces`: a safety cap, not a sampling setting.
inline constexpr int kDefaultMaxBounces = 1000;
inline constexpr int kMaxBouncesLimit = 100000;
/// Default `sampling.replicates`: independent randomised replicates per pixel, whose spread is the
/// variance channels' estimate (renderer.h). Two ("dual buffer"): every consumer of the variance
/// pools it over a region or a neighbourhood, whose degrees of freedom are then many times R − 1,
/// and each replicate keeps spp/2 points of one net (docs/simulation.md, "Why R = 2").
inline constexpr int kDefaultReplicates = 2;
/// Replicates for error bars that stand alone per pixel (Student's t with R − 1 = 15 dof: |z| > 5
/// in 0.016 % of pixels): `sampling.replicates: 16`.
inline constexpr int kPerPixelReplicates = 16;
inline constexpr int kMaxReplicates = 1024;

/// How the renderer estimates each vertex's reflected radiance (renderer.h): the plain path-traced
/// estimate, or with the reflection control variate (e0 − ε)·L_ref, exact by Kirchhoff's law, plus
/// the sampled reflection of L_in − L_ref (lower noise; docs/simulation.md).
enum class Estimator { plain, control_variate };

/// The names of scene files and the CLI: "plain", "control-variate".
std::string_view estimator_name(Estimator estimator);
/// The estimator called `name`, or nullopt if none is.
std::optional<Estimator> estimator_from_name(std::string_view name);

struct SamplingSettings {
    int samples_per_pixel = 16;
    /// Safety cap on the reflections followed after the camera's first hit. Paths end by Russian
    /// roulette (unbiased, renderer.h) long before it; a low cap truncates paths, which darkens
    /// closed reflective scenes (an all-aluminium box at 4 bounces: −87 % of L_bb).
    int max_bounces = kDefaultMaxBounces;
    std::uint64_t seed = 1;
    Estimator estimator =
        Estimator::control_variate;  ///< RenderOptions::control_variate overrides it
    /// Independently scrambled replicates of each pixel's samples (1–kMaxReplicates; 1 keeps all of
    /// a pixel's samples in one net, the lowest noise, and leaves the variance channels NaN; more
    /// give the per-pixel variance more degrees of freedom at the price of noise); a render uses
    /// replicate_count() of them.
    int replicates = kDefaultReplicates;
};

/// Replicates a render draws: min(replicates, spp) (one replicate per sample at low spp).
int replicate_count(const SamplingSettings& sampling);
/// Samples per pixel a render draws: spp rounded up to a multiple of replicate_count(), so that
/// every replicate has the same number of points (identically distributed replicate means: the
/// variance estimate's degrees of freedom are exactly replicates − 1). The EXR's `spp` records this
/// count.
int rendered_samples_per_pixel(const SamplingSettings& sampling);

/// Empty if `max_bounces` is acceptable (0–kMaxBouncesLimit), else what was expected; the one rule
/// for the scene file's sampling.max_bounces and the CLI's --max-bounces.
std::string max_bounces_problem(int max_bounces);

/// A material as used by the renderer: its pBRDF and where it came from.
struct SceneMaterial {
    std::string name;
    std::string source;  ///< file it was read from, or "inline in <scene>"
    std::shared_ptr<const materials::PolarizedBrdf> brdf;
};

struct SceneObject {
    std::string name;
    /// Index into Scene::materials: the object's material, or with per-face materials that of its
    /// first triangle.
    std::uint32_t material = 0;
    /// Per-face materials of a mesh file (the scene's `materials:` mapping): per triangle, an index
    /// into Scene::materials. Empty when the whole object is `material`.
    std::vector<std::uint32_t> triangle_materials;
    TemperatureField temperature;

    /// Index into Scene::materials of the material at triangle `primitive` (SurfaceHit::primitive).
    std::uint32_t material_at(std::uint32_t primitive) const {
        return triangle_materials.empty() ? material : triangle_materials[primitive];
    }
};

struct Scene {
    std::filesystem::path file;
    PinholeCamera camera;
    Band band;
    Sky sky;
    std::optional<Sun> sun;
    SamplingSettings sampling;
    std::vector<SceneMaterial> materials;
    std::vector<SceneObject> objects;  ///< index = RayTracer object index
    std::shared_ptr<RayTracer> tracer;
};

/// Loads a scene file. Every error names the file, line and field (unknown keys, wrong types, a
/// missing mesh or material file, an unknown material name).
Scene load_scene(const std::filesystem::path& path);
/// Same from an already parsed scene (a sweep point's overrides via ConfigNode::with_value, a
/// Python dict): relative paths resolve against the directory of `root.file()`, which becomes
/// Scene::file.
Scene load_scene(const ConfigNode& root);

}  // namespace tirpol::simulation
