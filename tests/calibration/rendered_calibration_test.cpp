// Geometric calibration end to end with the renderer as the source of truth: a heated
// checkerboard rendered through a known lens at 15 poses is detected in the EXR frames and
// calibrated; fx fy cx cy come back within 0.5 %, the distortion within its reported 2σ, the RMS
// reprojection error is < 0.1 px without noise and grows as it should with sensor noise. A board at
// 10 m gives the pose from its corners as surveyed control points within 0.1° and 1 cm.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rendered_frames.h"
#include "test_support.h"
#include "tirpol/calibration/geometric_calibration.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/simulation/pinhole_camera.h"
#include "tirpol/simulation/renderer.h"
#include "tirpol/simulation/scene.h"

namespace tirpol {
namespace {

/// 15 views: the board tilted 20–40° toward the camera from all around, at 1.1–1.3 m, shifted in
/// the image so the corners of the frame (where distortion is largest) are covered, with some roll.
std::vector<test::BoardView> calibration_views() {
    return simulation::board_calibration_views(15, test::truth_lens().fx, test::truth_lens().width);
}

class RenderedCalibration : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        s_dir = new test::TempDir("tirpol-geocal");
        s_frames = new test::RenderedFrames(
            test::render_views(*s_dir, test::HeatedBoard{}, calibration_views(), 8));
    }
    static void TearDownTestSuite() {
        delete s_frames;
        delete s_dir;
    }
    static test::TempDir* s_dir;
    static test::RenderedFrames* s_frames;
};
test::TempDir* RenderedCalibration::s_dir = nullptr;
test::RenderedFrames* RenderedCalibration::s_frames = nullptr;

TEST_F(RenderedCalibration, RecoversTheTruthLensNoiseFree) {
    const auto target = calibration::CalibrationTarget::parse(test::HeatedBoard{}.target());
    const auto r = calibration::calibrate_geometric_frames(s_frames->frames, target);
    EXPECT_TRUE(r.frames_without_target.empty());
    test::expect_recovered(r, 15, 0.1);
    for (const auto& v : r.views) EXPECT_FALSE(v.outlier) << v.name << " " << v.rms_px;
    std::printf("noise-free: fx %.3f fy %.3f cx %.3f cy %.3f k1 %.5f RMS %.4f px\n", r.model.fx,
                r.model.fy, r.model.cx, r.model.cy, r.model.distortion[0], r.model.rms_px);
}

TEST_F(RenderedCalibration, WithSensorNoiseTheRmsGrowsAndTheLensIsStillRecovered) {
    // NETD-like noise: 1.5 % of the hot–cold radiance contrast per pixel (≈ 0.2 K on a 15 K board).
    test::TempDir dir;
    std::mt19937 rng(42);
    std::vector<std::filesystem::path> noisy;
    for (std::size_t i = 0; i < s_frames->images.size(); ++i) {
        Image frame = s_frames->images[i];
        auto& s0 = frame.channel("S0");
        const auto [lo, hi] = std::minmax_element(s0.begin(), s0.end());
        std::normal_distribution<float> noise(0.0f, 0.015f * (*hi - *lo));
        for (float& v : s0) v += noise(rng);
        noisy.push_back(dir / fmt::format("noisy{:02}.exr", i));
        write_exr(noisy.back(), frame);
    }
    const auto target = calibration::CalibrationTarget::parse(test::HeatedBoard{}.target());
    const auto clean = calibration::calibrate_geometric_frames(s_frames->frames, target);
    const auto r = calibration::calibrate_geometric_frames(noisy, target);
    EXPECT_GT(r.model.rms_px, clean.model.rms_px) << "noise must show in the reprojection error";
    test::expect_recovered(r, 15, 0.3);
    std::printf("noisy: fx %.3f fy %.3f cx %.3f cy %.3f RMS %.4f px\n", r.model.fx, r.model.fy,
                r.model.cx, r.model.cy, r.model.rms_px);
}

TEST(RenderedPose, BoardCornersAtTenMetresGiveThePose) {
    // A 7.2 m × 5.6 m board of 0.8 m squares (a painted wall) standing 10 m in front of a
    // camera 2.5 m up; its inner corners serve as surveyed control points spread over 4.8 m × 3.2
    // m; the calibrated camera is the truth lens. 48 samples per pixel keep the Monte-Carlo edge
    // noise below 0.03 px.
    test::TempDir dir;
    test::HeatedBoard board;
    board.squares_x = 7;
    board.squares_y = 5;
    board.square_m = 0.8;
    board.texels_per_square = 16;
    board.centre = Vec3(0.3, 10.0, 2.5);
    board.standing = true;
    write_camera_model(dir / "truth_lens.yaml", test::truth_lens());
    const Vec3 position(0.1, 0.2, 2.5), look_at(0.4, 10.0, 2.3);
    test::write_text(dir / "scene.yaml",
                     test::board_scene(board.write(dir.path()), "truth_lens.yaml", position,
                                       look_at, world_up(), 48));
    const simulation::Scene scene = simulation::load_scene(dir / "scene.yaml");
    const Image image = simulation::render(scene);
    const auto target = calibration::CalibrationTarget::parse(board.target());
    const auto view = calibration::detect_target(image.channel("S0"), image.width(), image.height(),
                                                 target, "pose view");
    ASSERT_TRUE(view.has_value());
    // Match each detected corner to the board corner whose projection is nearest (the detector's
    // order may start at either end of the board).
    std::vector<calibration::ControlPoint> points;
    for (int r = 0; r < board.squares_y - 1; ++r)
        for (int c = 0; c < board.squares_x - 1; ++c) {
            const Vec3 world = board.inner_corner(c, r);
            const Vec2 predicted =
                *scene.camera.project(world) - Vec2(0.5, 0.5);  // → OpenCV convention
            Vec2 best = view->points_px.front();
            for (const Vec2& p : view->points_px)
                if ((p - predicted).norm() < (best - predicted).norm()) best = p;
            ASSERT_LT((best - predicted).norm(), 1.0);
            points.push_back({fmt::format("c{}r{}", c, r), world, best});
        }
    const auto result = calibration::estimate_pose(test::truth_lens(), points);
    const CameraPose truth = scene.camera.pose();
    const double angle_deg = rad_to_deg(
        Eigen::AngleAxisd(result.pose.camera_from_world * truth.camera_from_world.transpose())
            .angle());
    const double offset_m = (result.pose.position_m() - truth.position_m()).norm();
    EXPECT_LT(angle_deg, 0.1);
    EXPECT_LT(offset_m, 0.01);
    std::printf("pose at 10 m: %.4f° %.4f m, RMS %.3f px, 1σ position (%.4f %.4f %.4f) m\n",
                angle_deg, offset_m, result.pose.rms_px, result.pose.position_sigma_m.x(),
                result.pose.position_sigma_m.y(), result.pose.position_sigma_m.z());
}

}  // namespace
}  // namespace tirpol
