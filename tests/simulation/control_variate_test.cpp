// The reflection control variate (RenderOptions::control_variate, renderer.h): each vertex's
// reflected radiance is estimated as (e0 − ε)·L_ref + sampled ∫M·(L_in − L_ref)·cosθi dωi. By
// Kirchhoff's law (paper eq 5) the first term is the exact reflection of an unpolarized L_ref, so
// the estimator is unbiased for any L_ref that does not depend on the sampled direction. Checked
// here: in an isothermal enclosure it is exact (every term telescopes to L_bb), and in an open
// scene with a cold sky, a warm wall and the sun it agrees with the plain path-traced estimator
// within the reported errors while its S1 noise is lower.

#include <gtest/gtest.h>

#include <cmath>

#include "scene_fixtures.h"

namespace tirpol::simulation {
namespace {

using tirpol::test::TempDir;

const char* kRoughPaint =
    "{name: rough, source: test, model: microfacet, refractive_index: {n: 1.6, k: 0.1}, "
    "parameters: {sigma: 0.2, bias: 0.1, tau_deg: 20, omega_deg: 60, rho_d: 0.05, rho_v: 0.02}}";

/// Ground and ball of `material` (a YAML mapping or a library name) under a uniform sky, all at 290
/// K; with `with_objects` false only a small plate behind the camera: every pixel sees the sky.
std::string enclosure(const std::string& material, bool with_objects) {
    std::string yaml =
        test::scene_header(16, 12, 8, 1000,
                           "fov_deg: 40, position: [0, -4, 1.2], look_at: [0, 0, 0.4]",
                           "{type: uniform, temperature: 290}") +
        "objects:\n";
    if (!with_objects)
        return yaml +
               "  - {name: behind, geometry: {type: plane, size: [0.1, 0.1]}, transform: "
               "{translate: [0, -9, 0]}, "
               "material: " +
               material + ", temperature: 290}\n";
    return yaml +
           "  - {name: ground, geometry: {type: plane, size: [6, 6]}, material: " + material +
           ", temperature: 290}\n"
           "  - {name: ball, geometry: {type: sphere, radius: 0.5}, transform: {translate: [0, 0, "
           "0.8]}, material: " +
           material + ", temperature: 290}\n";
}

TEST(ControlVariate, IsothermalEnclosureIsExactInEveryPixel) {
    TempDir dir;
    // Each sample's wavelength depends only on (seed, pixel, sample), so the sky-only render with
    // the same seed draws the same wavelengths: its S0 is the band's spectral estimate that a
    // perfect blackbody pixel gets, spectral sampling noise included.
    for (const char* material :
         {test::kSmoothPaint, test::kGreyDiffuse, kRoughPaint, "bare_aluminium"}) {
        const Image img =
            render(test::load_scene_text(dir, enclosure(material, true), "scene.yaml"));
        const Image sky =
            render(test::load_scene_text(dir, enclosure(material, false), "sky.yaml"));
        const double l_bb =
            test::load_scene_text(dir, enclosure(material, false), "sky.yaml").band.radiance(290.0);
        std::size_t surface_pixels = 0;
        for (std::size_t i = 0; i < img.pixel_count(); ++i) {
            surface_pixels += img.channel("object_id")[i] >= 0.0f;
            // Exact up to rounding: emission ε·L_bb and the control variate's (e0 − ε)·L_bb add up
            // to e0·L_bb at each vertex, and every sampled L_in − L_ref is zero.
            ASSERT_NEAR(img.channel("S0")[i], sky.channel("S0")[i], 1e-6 * l_bb)
                << material << " pixel " << i;
            for (const char* c : {"S1", "S2", "S3"})
                ASSERT_NEAR(img.channel(c)[i], 0.0, 1e-6 * l_bb) << material << " " << c;
        }
        EXPECT_GT(surface_pixels, img.pixel_count() / 2) << material;
    }
}

/// A warm rough-paint ball and a glossy-paint wall on concrete under a cold clear sky and the sun.
Scene open_scene(const TempDir& dir, std::uint64_t seed) {
    std::string yaml =
        test::scene_header(40, 30, 64, 1000,
                           "fov_deg: 45, position: [0, -5, 1.5], look_at: [0, 0, 0.6]",
                           "{type: clear_sky, air_temperature: 275, zenith_emissivity: 0.7}") +
        "sun: {elevation_deg: 35, azimuth_deg: 200}\n"
        "objects:\n"
        "  - {name: ground, geometry: {type: plane, size: [30, 30]}, material: concrete, "
        "temperature: 285}\n"
        "  - {name: wall, geometry: {type: box, size: [4, 0.2, 2]}, transform: {translate: [0, "
        "1.5, 1], "
        "rotate_deg: [0, 0, 20]}, material: glossy_black_paint, temperature: 300}\n"
        "  - {name: ball, geometry: {type: sphere, radius: 0.6}, transform: {translate: [0, 0, "
        "0.6]}, "
        "material: " +
        std::string(kRoughPaint) + ", temperature: 320}\n";
    Scene scene = test::load_scene_text(dir, yaml, "open" + std::to_string(seed) + ".yaml");
    scene.sampling.seed = seed;
    return scene;
}

TEST(ControlVariate, OpenSceneMatchesThePlainEstimatorWithLowerNoise) {
    TempDir dir;
    const Image plain = render(open_scene(dir, 1), test::without_control_variate());
    const Image with_cv = render(open_scene(dir, 2));
    // Per object (material_id of the pixel-centre ray): the means of the two estimators over the
    // object's pixels differ by less than 5 of their pooled standard errors in S0, S1 and S2.
    for (float object = 0.0f; object < 3.0f; object += 1.0f) {
        for (const char* c : {"S0", "S1", "S2"}) {
            double diff = 0.0, var = 0.0;
            std::size_t n = 0;
            for (std::size_t i = 0; i < plain.pixel_count(); ++i) {
                if (plain.channel("object_id")[i] != object) continue;
                diff += with_cv.channel(c)[i] - plain.channel(c)[i];
                var += with_cv.channel(std::string(c) + "_var")[i] +
                       plain.channel(std::string(c) + "_var")[i];
                ++n;
            }
            ASSERT_GT(n, 20u) << "object " << object;
            const double sigma = std::sqrt(var) / static_cast<double>(n);
            diff /= static_cast<double>(n);
            EXPECT_LE(std::abs(diff), 5.0 * sigma)
                << "object " << object << " " << c << ": mean difference " << diff << ", pooled σ "
                << sigma;
        }
    }
    // Over all surface pixels, the control variate lowers the S1 variance (the sampled part is the
    // reflection of L_in − L_ref instead of L_in).
    double var_plain = 0.0, var_cv = 0.0;
    for (std::size_t i = 0; i < plain.pixel_count(); ++i)
        if (plain.channel("object_id")[i] >= 0.0f) {
            var_plain += plain.channel("S1_var")[i];
            var_cv += with_cv.channel("S1_var")[i];
        }
    std::printf(
        "open scene, 64 spp: summed S1 variance, plain %.4g, control variate %.4g (ratio %.2f)\n",
        var_plain, var_cv, var_plain / var_cv);
    EXPECT_LT(var_cv, 0.5 * var_plain);
}

// The scene file's sampling.estimator chooses the estimator (CLI --estimator overrides it), an
// explicit RenderOptions::control_variate overrides both, and the EXR header records which one ran.
TEST(ControlVariate, SceneFileChoosesTheEstimatorAndTheImageRecordsIt) {
    TempDir dir;
    Scene scene = open_scene(dir, 1);
    scene.camera = scene.camera.resized(10, 8);
    const Image by_default = render(scene);
    EXPECT_EQ(std::get<std::string>(by_default.attributes().at("estimator")), "control-variate");
    const Image plain_by_option = render(scene, test::without_control_variate());
    scene.sampling.estimator = Estimator::plain;
    const Image plain = render(scene);
    EXPECT_EQ(std::get<std::string>(plain.attributes().at("estimator")), "plain");
    EXPECT_EQ(plain.channel("S1"), plain_by_option.channel("S1"));
    EXPECT_NE(plain.channel("S1"), by_default.channel("S1"));
    RenderOptions forced;
    forced.control_variate = true;
    EXPECT_EQ(render(scene, forced).channel("S1"), by_default.channel("S1"));
}

}  // namespace
}  // namespace tirpol::simulation
