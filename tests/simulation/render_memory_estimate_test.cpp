// A render's memory is estimated before anything is allocated (render --spp 2147483647 on 2×2
// pixels reached 8.3 GB; a 16384×4096 render took 4.4 GB unannounced): the estimate bounds what the
// image really holds, and render() refuses spp beyond the limits table before building anything.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "render_memory.h"
#include "scene_fixtures.h"
#include "tirpol/core/error.h"
#include "tirpol/core/limits.h"

namespace tirpol::simulation {
namespace {

using tirpol::test::TempDir;

std::string scene_text(int spp) {
    return test::scene_header(6, 4, spp, 4, "fov_deg: 30, position: [0, -3, 1], look_at: [0, 0, 0]",
                              "{type: uniform, temperature: 260}") +
           "objects:\n  - {name: ground, geometry: {type: plane, size: [10, 10]}, material: "
           "flat_black_paint, "
           "temperature: 290}\n";
}

Scene small_scene(const TempDir& dir, int spp) {
    return test::load_scene_text(dir, scene_text(spp));
}

TEST(RenderMemoryEstimate, EstimateCoversEveryChannelTheImageHolds) {
    const TempDir dir;
    RenderOptions options;
    options.emissivity_cache_dir = std::filesystem::path{};  // memory cache only
    const Image image = render(small_scene(dir, 2), options);
    const std::uint64_t held = static_cast<std::uint64_t>(image.channel_names().size()) *
                               sizeof(float) * static_cast<std::uint64_t>(image.width()) *
                               static_cast<std::uint64_t>(image.height());
    EXPECT_GE(render_memory_estimate_bytes(image.width(), image.height()), held);
    // The report's 16384×4096 image: 18 channels × 4 bytes = 4.8 GB; the estimate says so before
    // rendering.
    EXPECT_GE(render_memory_estimate_bytes(16384, 4096), std::uint64_t{18} * 4 * 16384 * 4096);
}

TEST(RenderMemoryEstimate, SamplesPerPixelBeyondTheLimitAreRefusedBeforeRendering) {
    const TempDir dir;
    Scene scene = small_scene(dir, 1);
    scene.sampling.samples_per_pixel = limits::kMaxSamplesPerPixel + 1;
    try {
        (void)render(scene);
        FAIL() << "rendered at " << scene.sampling.samples_per_pixel << " spp";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), testing::HasSubstr("expected 1 to 1048576 samples per pixel"));
    }
    // The scene file is held to the same limit, with its location.
    try {
        (void)test::load_scene_text(dir, scene_text(2147483647), "spp.yaml");
        FAIL() << "loaded a scene with 2147483647 spp";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(),
                    testing::AllOf(testing::HasSubstr("spp.yaml:"), testing::HasSubstr("1048576")));
    }
}

}  // namespace
}  // namespace tirpol::simulation
