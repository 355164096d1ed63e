// Circle grids through the same calibration path as the checkerboard: a heated plate
// behind a cold mask with round holes — OpenCV's symmetric and asymmetric grids — rendered through
// the truth lens at 15 poses. Detection (the blob detector set
// for thermal frames) and calibration recover fx fy cx cy within the 0.5 % and the
// distortion within 2σ, with hot discs and with the polarity inverted; a grid that is not in the
// frames is an error naming them.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "rendered_frames.h"
#include "tirpol/core/error.h"

namespace tirpol {
namespace {

using Pattern = simulation::HeatedBoard::Pattern;

/// Cells of 6 cm with 3 cm discs: circles:8x6:0.06, or acircles:4x7:0.06 (an asymmetric grid needs
/// an odd number of rows).
test::HeatedBoard circle_board(Pattern pattern) {
    test::HeatedBoard board;
    board.pattern = pattern;
    board.squares_x = 8;
    board.squares_y = pattern == Pattern::AsymmetricCircles ? 7 : 6;
    return board;
}

/// The 15 views of rendered_calibration_test.cpp, but rolled ±180° about the optical axis: blob
/// centroids carry a perspective bias of a few hundredths of a pixel that the ±25° rolls of those
/// views let through into cx by ~1.7 px (0.5 %); rolled views constrain the principal point ~2.5×
/// better (docs/twin.md, "Known limits").
std::vector<test::BoardView> calibration_views() {
    return simulation::board_calibration_views(15, test::truth_lens().fx, test::truth_lens().width,
                                               40.0, 180.0);
}

/// Every detected centre lies on the projection of a disc centre (the detector's order may start at
/// either end of the grid): the largest distance, px.
double worst_centre_error_px(const calibration::TargetView& view, const test::HeatedBoard& board,
                             const test::BoardView& pose) {
    test::TempDir dir;
    write_camera_model(dir / "lens.yaml", test::truth_lens());
    test::write_text(dir / "scene.yaml",
                     test::board_scene(board.write(dir.path()), "lens.yaml", pose.position,
                                       pose.look_at, pose.up, 1));
    const simulation::Scene scene = simulation::load_scene(dir / "scene.yaml");
    double worst = 0.0;
    for (const Vec2& found : view.points_px) {
        double nearest = 1e9;
        for (const Vec3& centre : board.features())
            nearest = std::min(nearest,
                               (found - (*scene.camera.project(centre) - Vec2(0.5, 0.5))).norm());
        worst = std::max(worst, nearest);
    }
    return worst;
}

class RenderedCircleGrid : public ::testing::TestWithParam<Pattern> {};

TEST_P(RenderedCircleGrid, RecoversTheTruthLensInBothPolarities) {
    test::TempDir dir;
    const test::HeatedBoard board = circle_board(GetParam());
    const auto views = calibration_views();
    const test::RenderedFrames rendered = test::render_views(dir, board, views, 8);
    const auto target = calibration::CalibrationTarget::parse(board.target());

    const auto view =
        calibration::detect_target(rendered.images[0].channel("S0"), 640, 512, target, "view 0");
    ASSERT_TRUE(view.has_value());
    EXPECT_EQ(view->points_px.size(), target.point_count());
    // Blob centroids of discs seen at 20–40° through a strong lens: within a few tenths of a pixel
    // of the projected centres (the ellipse's centroid is not the projected centre; Heikkilä, IEEE
    // TPAMI 22(10), 2000).
    EXPECT_LT(worst_centre_error_px(*view, board, views[0]), 0.3);

    const auto hot = calibration::calibrate_geometric_frames(rendered.frames, target);
    EXPECT_TRUE(hot.frames_without_target.empty());
    test::expect_recovered(hot, 15, 0.15);

    // Cold discs on a warm plate (a cold mask with holes in front of the cold sky).
    std::vector<std::filesystem::path> inverted;
    for (std::size_t i = 0; i < rendered.images.size(); ++i) {
        Image frame = rendered.images[i];
        auto& s0 = frame.channel("S0");
        const auto [lo, hi] = std::minmax_element(s0.begin(), s0.end());
        const float sum = *lo + *hi;
        for (float& v : s0) v = sum - v;
        inverted.push_back(dir / fmt::format("inverted{:02}.exr", i));
        write_exr(inverted.back(), frame);
    }
    const auto cold = calibration::calibrate_geometric_frames(inverted, target);
    test::expect_recovered(cold, 15, 0.15);
    std::printf(
        "%s: fx %.3f fy %.3f cx %.3f cy %.3f k1 %.5f RMS %.4f px; inverted fx %.3f cx %.3f RMS "
        "%.4f px\n",
        target.to_string().c_str(), hot.model.fx, hot.model.fy, hot.model.cx, hot.model.cy,
        hot.model.distortion[0], hot.model.rms_px, cold.model.fx, cold.model.cx, cold.model.rms_px);

    // A grid of another size is not found: the error says in which frames.
    calibration::CalibrationTarget wrong = target;
    wrong.columns += 1;
    try {
        calibration::calibrate_geometric_frames(rendered.frames, wrong);
        ADD_FAILURE() << "a " << wrong.to_string() << " grid was found in frames of "
                      << target.to_string();
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("found in 0 of 15 frames"), std::string::npos) << message;
        EXPECT_NE(message.find(rendered.frames[14].string()), std::string::npos) << message;
    }
}

INSTANTIATE_TEST_SUITE_P(Grids, RenderedCircleGrid,
                         ::testing::Values(Pattern::Circles, Pattern::AsymmetricCircles),
                         [](const auto& grid) {
                             return grid.param == Pattern::Circles ? "Symmetric" : "Asymmetric";
                         });

}  // namespace
}  // namespace tirpol
