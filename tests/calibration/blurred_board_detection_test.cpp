// detect_target() on two of the synthetic blurred, low-contrast LWIR views of blurred_boards.h
// (the 16 views and OpenCV's detectors on them: bench/board_detection_bench.cpp): every corner
// found, and within a sub-pixel RMS of the corners the views were rendered from.

#include <gtest/gtest.h>

#include "blurred_boards.h"
#include "tirpol/calibration/target_detection.h"

namespace tirpol::calibration {
namespace {

double detected_rms_px(int view_index) {
    const auto target = CalibrationTarget::parse("checkerboard:9x6:0.05");
    const test::BlurredBoard b = test::blurred_board_view(target, view_index);
    const auto view = detect_target(b.plane, test::kBoardWidth, test::kBoardHeight, target,
                                    "view " + std::to_string(view_index));
    if (!view) return -1.0;
    EXPECT_EQ(view->points_px.size(), target.point_count());
    return test::corner_rms_px(b.corners_px, view->points_px);
}

TEST(BlurredBoardDetection, EasyViewFortyCountsBlurOnePointFivePx) {
    // View 0: 40 counts of contrast, 1.5 px blur, 10° tilt, hot squares.
    const double rms = detected_rms_px(0);
    ASSERT_GE(rms, 0.0) << "board not found";
    EXPECT_LT(rms, 0.25);
}

TEST(BlurredBoardDetection, HardViewTwelveCountsTiltedFortyTwoDeg) {
    // View 12: 12 counts of contrast (6 × the noise), 1.5 px blur, 42° tilt, the lowest contrast.
    const double rms = detected_rms_px(12);
    ASSERT_GE(rms, 0.0) << "board not found";
    EXPECT_LT(rms, 0.8);
}

}  // namespace
}  // namespace tirpol::calibration
