// `tirpol compare --camera CAM.yaml` through the real executable: a simulation rendered
// through the measured camera's calibrated model (distortion, principal point off centre) is
// compared on the measured pixel grid without a warp, the report states the method and the residual
// misalignment measured from the images; a simulation rendered through another lens is refused.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "cli_runner.h"
#include "test_support.h"
#include "tirpol/core/camera_model.h"

namespace {

using namespace tirpol;
using tirpol::test::run_cli;

CameraModel lens() {
    CameraModel m;
    m.width = 80;
    m.height = 64;
    m.fx = 95.0;
    m.fy = 95.4;
    m.cx = 41.3;
    m.cy = 30.8;
    m.distortion = {-0.3, 0.12, 0.0008, -0.0005, -0.03};
    return m;
}

/// A warm ball on the ground seen through the camera model `model` (relative to the scene file).
void write_scene(const test::TempDir& dir, const std::string& name, const std::string& model,
                 int seed) {
    test::write_text(
        dir / name,
        fmt::format("band: {{lo_um: 8, hi_um: 14}}\nsampling: {{spp: 32, max_bounces: 0, seed: "
                    "{}}}\nmaterials_dir: {}\n"
                    "camera: {{model: {}, position: [0, -3, 1.2], look_at: [0, 0, 0.4]}}\n"
                    "sky: {{type: uniform, temperature: 230}}\nobjects:\n"
                    "  - {{name: ground, geometry: {{type: plane, size: [10, 10]}}, material: "
                    "concrete, temperature: 280}}\n"
                    "  - {{name: ball, geometry: {{type: sphere, radius: 0.4}}, transform: "
                    "{{translate: [0, 0, 0.4]}}, "
                    "material: flat_black_paint, temperature: 305}}\n",
                    seed, (test::source_dir() / "config" / "materials").string(), model));
}

TEST(CompareCameraCli, ASimulationRenderedThroughTheModelIsComparedWithoutAWarp) {
    test::TempDir dir;
    write_camera_model(dir / "cam.yaml", lens());
    write_scene(dir, "measured.yaml", "cam.yaml", 2);
    write_scene(dir, "simulated.yaml", "cam.yaml", 1);
    for (const char* scene : {"measured", "simulated"}) {
        const auto r = run_cli(fmt::format("render {} -o {} --threads 2 --quiet",
                                           (dir / (std::string(scene) + ".yaml")).string(),
                                           dir.path().string()));
        ASSERT_EQ(r.exit_code, 0) << r.out;
    }
    const std::string common =
        fmt::format("compare --measured {} --simulated {} --measured-sigma 0.05",
                    (dir / "measured.exr").string(), (dir / "simulated.exr").string());
    auto run = run_cli(common + fmt::format(" --camera {} -o {}", (dir / "cam.yaml").string(),
                                            (dir / "report").string()));
    ASSERT_EQ(run.exit_code, 0) << run.out;
    const std::string stated = "registration: camera-model (identity), residual misalignment ";
    const auto at = run.out.find(stated);
    ASSERT_NE(at, std::string::npos) << run.out;
    // Same lens and pose: only the two renders' Monte Carlo noise separates them (phase correlation
    // of 80×64 S0 gradients at 32 spp: 16 replicates of 2 points).
    EXPECT_LT(std::stod(run.out.substr(at + stated.size())), 0.25) << run.out;
    EXPECT_NE(run.out.find("calibrated camera model " + (dir / "cam.yaml").string()),
              std::string::npos)
        << run.out;

    // A simulation rendered through another lens is refused, naming what differs.
    CameraModel other = lens();
    other.distortion[0] = -0.2;
    write_camera_model(dir / "other.yaml", other);
    run = run_cli(common + fmt::format(" --camera {} -o {}", (dir / "other.yaml").string(),
                                       (dir / "r2").string()));
    EXPECT_EQ(run.exit_code, 1) << run.out;
    EXPECT_NE(run.out.find("rendered with distortion"), std::string::npos) << run.out;

    // --camera decides the registration: another method with it is a usage error.
    run = run_cli(common + fmt::format(" --camera {} --registration auto -o {}",
                                       (dir / "cam.yaml").string(), (dir / "r3").string()));
    EXPECT_EQ(run.exit_code, 2) << run.out;
}

}  // namespace
