// RenderOptions::cancel (how the Python module stops a render on Ctrl-C) and load_scene from an
// already parsed ConfigNode (how a Python dict becomes a scene).

#include <gtest/gtest.h>

#include <atomic>

#include "scene_fixtures.h"
#include "tirpol/core/config.h"
#include "tirpol/core/interrupt_signals.h"
#include "tirpol/simulation/renderer.h"

namespace tirpol::simulation {
namespace {

using tirpol::test::TempDir;

std::string ball_scene() {
    return test::scene_header(12, 10, 4, 4, "fov_deg: 30, position: [0, -5, 0], look_at: [0, 0, 0]",
                              "{type: uniform, temperature: 260}") +
           "objects:\n  - {name: ball, geometry: {type: sphere, radius: 1}, material: " +
           test::kSmoothPaint + ", temperature: 300}\n";
}

TEST(RenderCancel, SetFlagStopsTheRenderWithCancelled) {
    TempDir dir;
    const Scene scene = test::load_scene_text(dir, ball_scene());
    std::atomic<bool> cancel{true};
    RenderOptions options;
    options.cancel = &cancel;
    options.emissivity_cache_dir = std::filesystem::path{};
    EXPECT_THROW(render(scene, options), Cancelled);
}

TEST(RenderCancel, ClearFlagRendersTheSameImageAsNoFlag) {
    TempDir dir;
    const Scene scene = test::load_scene_text(dir, ball_scene());
    std::atomic<bool> cancel{false};
    RenderOptions options;
    options.emissivity_cache_dir = std::filesystem::path{};
    const Image plain = render(scene, options);
    options.cancel = &cancel;
    const Image flagged = render(scene, options);
    EXPECT_EQ(plain.channel("S0"), flagged.channel("S0"));
    EXPECT_EQ(plain.channel("S1"), flagged.channel("S1"));
}

TEST(SceneFromConfig, ParsedTextLoadsLikeTheFileAndResolvesPathsAgainstItsFolder) {
    TempDir dir;
    const Scene from_file = test::load_scene_text(dir, ball_scene());
    const Scene from_node =
        load_scene(ConfigNode::parse(ball_scene(), (dir.path() / "in_memory.yaml").string()));
    EXPECT_EQ(from_node.file, dir.path() / "in_memory.yaml");
    EXPECT_EQ(from_node.camera.width(), from_file.camera.width());
    RenderOptions options;
    options.emissivity_cache_dir = std::filesystem::path{};
    EXPECT_EQ(render(from_node, options).channel("S0"), render(from_file, options).channel("S0"));
}

}  // namespace
}  // namespace tirpol::simulation
