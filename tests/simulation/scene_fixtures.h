#pragma once
// Small scenes written as YAML for the simulation tests (so the tests go through the real loader).

#include <fmt/format.h>

#include <string>

#include "test_support.h"
#include "tirpol/simulation/renderer.h"
#include "tirpol/simulation/scene.h"

namespace tirpol::simulation::test {

/// A smooth dielectric (paint-like, n = 1.5 + 0.05i in the LWIR): inline material mapping.
inline const char* kSmoothPaint =
    "{name: smooth_paint, source: \"test: generic LWIR paint index\", model: smooth_fresnel, "
    "refractive_index: {n: 1.5, k: 0.05}}";
/// A grey diffuse surface.
inline const char* kGreyDiffuse =
    "{name: grey_diffuse, source: \"test\", model: lambertian, parameters: {reflectance: 0.3}}";

/// Render options without the reflection control variate (RenderOptions::control_variate): the
/// plain path-traced estimator, for tests of the BRDF sampling, Russian roulette and the error
/// bars, which the control variate would make exact (and vacuous) in an isothermal enclosure.
inline RenderOptions without_control_variate() {
    RenderOptions options;
    options.control_variate = false;
    return options;
}

/// `scene` with kPerPixelReplicates (16) replicates: for tests that compare each pixel with its own
/// error bar (|S − exact| ≤ 5σ per pixel), whose Student-t tails need ν = 15; the default two
/// replicates give one dof per pixel, meant to be pooled over regions (docs/simulation.md).
inline Scene with_per_pixel_error_bars(Scene scene) {
    scene.sampling.replicates = kPerPixelReplicates;
    return scene;
}

/// Writes `yaml` to `<dir>/<name>` and loads it.
inline Scene load_scene_text(const tirpol::test::TempDir& dir, const std::string& yaml,
                             const std::string& name = "scene.yaml") {
    tirpol::test::write_text(dir / name, yaml);
    return load_scene(dir / name);
}

/// Header of a scene: band (default 8–14 µm), sampling, camera.
inline std::string scene_header(int width, int height, int spp, int bounces,
                                const std::string& camera_body, const std::string& sky,
                                double band_lo_um = 8.0, double band_hi_um = 14.0) {
    return fmt::format(
        "band: {{lo_um: {}, hi_um: {}}}\n"
        "sampling: {{spp: {}, max_bounces: {}, seed: 7}}\n"
        "materials_dir: {}\n"
        "camera: {{resolution: [{}, {}], {}}}\n"
        "sky: {}\n",
        band_lo_um, band_hi_um, spp, bounces,
        (tirpol::test::source_dir() / "config" / "materials").string(), width, height, camera_body,
        sky);
}

}  // namespace tirpol::simulation::test
