// `tirpol calibrate pose` and `calibrate geometric` through the real executable: the pose file it
// writes puts the camera where it was, and bad input exits 1 naming the problem.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "cli_runner.h"
#include "test_support.h"
#include "tirpol/core/camera_model.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/image.h"
#include "truth_lens.h"

namespace {

using namespace tirpol;
using tirpol::test::run_cli;

TEST(GeometryCli, PoseFromControlPointsIsWrittenAndPrinted) {
    test::TempDir dir;
    write_camera_model(dir / "camera.yaml", tirpol::test::truth_lens());
    // Camera 1.5 m up at the origin looking north (x right = east, y down, z forward = north).
    CameraPose truth;
    truth.camera_from_world << 1, 0, 0, 0, 0, -1, 0, 1, 0;
    const Vec3 position(0.0, 0.0, 1.5);
    truth.translation_m = -truth.camera_from_world * position;
    std::string csv = "name,x_m,y_m,z_m,u_px,v_px\n";
    const std::vector<Vec3> world = {
        {-2, 9, 0}, {2, 9, 0},      {-2, 9, 2.5}, {2, 9, 2.5},
        {0, 12, 1}, {-2.5, 7, 0.3}, {2.5, 7, 1.8}};  // all inside the 640×512 view
    for (std::size_t i = 0; i < world.size(); ++i) {
        const Vec2 px = tirpol::test::truth_lens().project(truth.camera_from_world * world[i] +
                                                           truth.translation_m);
        csv += fmt::format("p{},{},{},{},{:.4f},{:.4f}\n", i, world[i].x(), world[i].y(),
                           world[i].z(), px.x(), px.y());
    }
    test::write_text(dir / "survey.csv", csv);
    const auto run = run_cli(
        fmt::format("calibrate pose --camera {} --points {} -o {}", (dir / "camera.yaml").string(),
                    (dir / "survey.csv").string(), (dir / "pose.yaml").string()));
    ASSERT_EQ(run.exit_code, 0) << run.out;
    EXPECT_NE(run.out.find("7 of 7 control points"), std::string::npos) << run.out;
    const CameraPose pose = read_camera_pose(dir / "pose.yaml");
    EXPECT_LT((pose.position_m() - position).norm(), 1e-3);
    EXPECT_EQ(pose.points, 7);
}

TEST(GeometryCli, BadInputExitsOneAndSaysWhy) {
    test::TempDir dir;
    write_camera_model(dir / "camera.yaml", tirpol::test::truth_lens());
    test::write_text(
        dir / "three.csv",
        "name,x_m,y_m,z_m,u_px,v_px\na,0,9,0,300,300\nb,1,9,0,380,300\nc,0,9,1,300,220\n");
    auto run = run_cli(fmt::format("calibrate pose --camera {} --points {} -o {}",
                                   (dir / "camera.yaml").string(), (dir / "three.csv").string(),
                                   (dir / "pose.yaml").string()));
    EXPECT_EQ(run.exit_code, 1) << run.out;
    EXPECT_NE(run.out.find("need at least 4"), std::string::npos) << run.out;
    EXPECT_FALSE(std::filesystem::exists(dir / "pose.yaml"));

    // Frames of a flat scene: the target is nowhere, and the message lists the frames.
    std::string frames;
    for (int i = 0; i < 5; ++i) {
        Image flat(64, 48);
        flat.add_channel("counts", 8000.0f + static_cast<float>(i));
        flat.channel("counts")[static_cast<std::size_t>(i)] =
            8100.0f;  // not constant, still no target
        const auto path = dir / fmt::format("flat{}.exr", i);
        write_exr(path, flat);
        frames += " " + path.string();
    }
    run = run_cli(fmt::format("calibrate geometric{} --target checkerboard:9x6:0.05 -o {}", frames,
                              (dir / "cam.yaml").string()));
    EXPECT_EQ(run.exit_code, 1) << run.out;
    EXPECT_NE(run.out.find("found in 0 of 5 frames"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("flat4.exr"), std::string::npos) << run.out;
    run = run_cli(fmt::format("calibrate geometric{} --target checkerboard:9x6 -o {}", frames,
                              (dir / "cam.yaml").string()));
    EXPECT_EQ(run.exit_code, 2) << run.out;  // a malformed --target is a usage error
    EXPECT_NE(run.out.find("checkerboard:COLSxROWS:SQUARE_M"), std::string::npos) << run.out;
}

}  // namespace
