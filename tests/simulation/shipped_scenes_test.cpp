// Every scene shipped in config/scenes loads and renders, and the paper's "panel contrast drops
// under trees" phenomenology (§4, ARCHITECTURE.md "Physics to get right") holds between the two
// tree scenes.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <string>

#include "scene_fixtures.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::simulation {
namespace {

std::filesystem::path scenes_dir() { return tirpol::test::source_dir() / "config" / "scenes"; }

/// The scene at a small resolution and sample count: enough to see each object, cheap enough for
/// CI.
Scene small(const std::filesystem::path& file, int width, int height, int spp) {
    Scene scene = load_scene(file);
    scene.camera = scene.camera.resized(width, height);
    scene.sampling.samples_per_pixel = spp;
    return scene;
}

/// The seven scenes of the paper's §4 that the docs list (docs/simulation.md); other files in
/// config/scenes are benchmark scenes (e.g. reflection_compare.yaml, where nothing emits).
const std::set<std::string> kPaperScenes = {
    "ball_on_snow_day",    "ball_on_snow_night", "panels_night",  "panels_pool_night",
    "panels_before_trees", "panels_under_trees", "vehicles_night"};

TEST(ShippedScenes, EveryShippedSceneLoadsAndRendersFiniteRealizableStokes) {
    std::set<std::string> rendered;
    for (const auto& entry : std::filesystem::directory_iterator(scenes_dir())) {
        if (entry.path().extension() != ".yaml") continue;
        SCOPED_TRACE(entry.path().filename().string());
        const Scene scene = small(entry.path(), 40, 30, 2);
        // The plain estimator, whose every sample is realizable: with the control variate a
        // sample's L_in − L_ref can be negative (unbiased, but a 2-spp mean need not be
        // realizable).
        const Image img = render(scene, test::without_control_variate());
        int surface_pixels = 0;
        for (int y = 0; y < img.height(); ++y)
            for (int x = 0; x < img.width(); ++x) {
                const double s0 = img.at("S0", x, y), s1 = img.at("S1", x, y),
                             s2 = img.at("S2", x, y), s3 = img.at("S3", x, y);
                ASSERT_TRUE(std::isfinite(s0) && std::isfinite(s1) && std::isfinite(s2) &&
                            std::isfinite(s3))
                    << "pixel " << x << "," << y;
                // Each sample's Stokes vector is realizable, so their mean is (convexity), up to
                // rounding.
                EXPECT_LE(std::sqrt(s1 * s1 + s2 * s2 + s3 * s3), s0 * (1 + 1e-9) + 1e-12)
                    << "pixel " << x << "," << y;
                // The paper's terrestrial scenes in the 8–14 µm band: brightness temperatures
                // between a clear sky and a sunlit roof.
                if (kPaperScenes.count(entry.path().stem().string())) {
                    const double t_b = scene.band.brightness_temperature(s0);
                    EXPECT_GT(t_b, 150.0) << "pixel " << x << "," << y;
                    EXPECT_LT(t_b, 400.0) << "pixel " << x << "," << y;
                }
                if (img.at("object_id", x, y) >= 0) ++surface_pixels;
            }
        EXPECT_GT(surface_pixels, 0);
        rendered.insert(entry.path().stem().string());
    }
    for (const std::string& name : kPaperScenes)
        EXPECT_TRUE(rendered.count(name)) << name << " was not found in config/scenes";
}

/// Mean S1 over the pixels of objects whose names start with "panel".
double mean_panel_s1(const Scene& scene, const Image& img) {
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x) {
            const double id = img.at("object_id", x, y);
            if (id < 0) continue;
            if (scene.objects.at(static_cast<std::size_t>(id)).name.rfind("panel", 0) != 0)
                continue;
            sum += img.at("S1", x, y);
            ++n;
        }
    EXPECT_GT(n, 50) << "too few panel pixels to compare";
    return n > 0 ? sum / n : 0.0;
}

// Paper §4 (panels before and under trees): open to the cold night sky, the panels' emission
// dominates and is vertically polarized (S1 < 0); under the canopy the warm leaves fill the
// specular direction, their reflection is polarized the other way and cancels part of it. In the
// shipped geometry the crowns fill only part of the panels' specular direction (the rest is still
// sky between and above them): at 160×128, 8 spp, seeds 1 and 99 give S1 = −0.0706 / −0.0707 in the
// open and −0.0552 / −0.0571 under the trees (a 20–22 % drop; seed-to-seed scatter ≤ 3 %), so a
// 10 % drop is required.
TEST(ShippedScenes, PanelPolarizationContrastDropsUnderTrees) {
    const Scene open = small(scenes_dir() / "panels_before_trees.yaml", 160, 128, 8);
    const Scene under = small(scenes_dir() / "panels_under_trees.yaml", 160, 128, 8);
    const double s1_open = mean_panel_s1(open, render(open));
    const double s1_under = mean_panel_s1(under, render(under));
    EXPECT_LT(s1_open, 0.0);
    EXPECT_LT(std::abs(s1_under), 0.9 * std::abs(s1_open))
        << "open " << s1_open << ", under trees " << s1_under;
}

}  // namespace
}  // namespace tirpol::simulation
