// `tirpol render` as one library call (simulation::run_render): the command line's overrides of a
// scene are applied or refused with an OptionValueError naming the option (the CLI exits 2 with it)
// before anything is written, and the files it reports are the ones on disk.

#include <gtest/gtest.h>

#include "scene_fixtures.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/output_guard.h"
#include "tirpol/simulation/render_output.h"

namespace tirpol::simulation {
namespace {

using tirpol::test::TempDir;

struct SceneFile {
    TempDir dir;
    RenderRunOptions options;
    SceneFile() {
        tirpol::test::write_text(
            dir / "ball.yaml",
            test::scene_header(12, 10, 4, 4,
                               "fov_deg: 30, position: [0, -5, 0], look_at: [0, 0, 0]",
                               "{type: uniform, temperature: 260}") +
                "objects:\n  - {name: ball, geometry: {type: sphere, radius: 1}, material: " +
                test::kSmoothPaint + ", temperature: 300}\n");
        options.scene = dir / "ball.yaml";
        options.output = dir / "out";
        options.show_progress = false;
    }
};

std::string refused_option(const RenderRunOptions& options) {
    try {
        run_render(options);
    } catch (const OptionValueError& e) {
        return e.option();
    } catch (const Error&) {
        return "(not an option error)";
    }
    return "";
}

TEST(RenderRun, RefusesOverridesTheSceneCannotTakeNamingTheOption) {
    SceneFile f;
    auto with = [&](auto change) {
        RenderRunOptions o = f.options;
        change(o);
        return refused_option(o);
    };
    EXPECT_EQ(with([](auto& o) { o.width = 8; }), "--width/--height");
    EXPECT_EQ(with([](auto& o) {
                  o.width = 0;
                  o.height = 4;
              }),
              "--width/--height");
    EXPECT_EQ(with([](auto& o) { o.samples_per_pixel = 0; }), "--spp");
    EXPECT_EQ(with([](auto& o) { o.max_bounces = -1; }), "--max-bounces");
    EXPECT_EQ(with([](auto& o) { o.estimator = "fancy"; }), "--estimator");
    EXPECT_FALSE(std::filesystem::exists(f.dir / "out")) << "written despite a refused override";
}

TEST(RenderRun, AppliesTheOverridesAndReportsTheFilesItWrote) {
    SceneFile f;
    f.options.width = 6;
    f.options.height = 5;
    f.options.samples_per_pixel = 2;
    const RenderRun run = run_render(f.options);
    EXPECT_EQ(run.width, 6);
    EXPECT_EQ(run.height, 5);
    EXPECT_GE(run.samples_per_pixel, 2);
    EXPECT_EQ(run.samples_per_pixel % run.replicates, 0);
    ASSERT_FALSE(run.written.empty());
    EXPECT_EQ(run.written.front(), f.dir / "out" / "ball.exr");
    const Image image = read_exr(run.written.front());
    EXPECT_EQ(image.width(), 6);
    EXPECT_EQ(image.height(), 5);
    const std::string text = render_run_text(run);
    EXPECT_NE(text.find("6×5"), std::string::npos) << text;
    for (const auto& p : run.written) {
        EXPECT_TRUE(std::filesystem::exists(p)) << p;
        EXPECT_NE(text.find(p.string()), std::string::npos) << text;
    }
}

TEST(RenderRun, KeepsAFileItDidNotWriteUnlessForced) {
    SceneFile f;
    f.options.width = 4;
    f.options.height = 3;
    f.options.samples_per_pixel = 1;
    std::filesystem::create_directories(f.dir / "out");
    tirpol::test::write_text(f.dir / "out" / "ball.exr", "someone else's file");
    EXPECT_THROW(run_render(f.options), OutputConflict);
    f.options.force = true;
    EXPECT_EQ(run_render(f.options).width, 4);
    EXPECT_EQ(read_exr(f.dir / "out" / "ball.exr").width(), 4);
}

}  // namespace
}  // namespace tirpol::simulation
