// The text of `tirpol calibrate pose`: the camera position is −Rᵀt (here R = I, t = (−1, −2, −3)
// gives (1, 2, 3) m), every control point's residual with outliers flagged, and the file written.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tirpol/calibration/geometric_calibration.h"

namespace tirpol::calibration {
namespace {

using ::testing::HasSubstr;

TEST(GeometryReport, PoseTextGivesPositionResidualsAndOutliers) {
    PoseResult r;
    r.pose.translation_m = Vec3(-1.0, -2.0, -3.0);
    r.pose.rms_px = 0.25;
    r.pose.points = 2;
    r.residual_px = {0.2, 7.5, 0.3};
    r.inlier = {true, false, true};
    const std::vector<ControlPoint> points = {{"pole", Vec3::Zero(), Vec2::Zero()},
                                              {"corner", Vec3::Zero(), Vec2::Zero()},
                                              {"door", Vec3::Zero(), Vec2::Zero()}};
    const std::string text = pose_estimation_text(r, points, "pose.yaml");
    EXPECT_THAT(text, HasSubstr("camera pose from 2 of 3 control points, RMS reprojection error "
                                "0.250 px\n"));
    EXPECT_THAT(text, HasSubstr("  position (world) 1.0000 2.0000 3.0000 m"));
    EXPECT_THAT(text, HasSubstr("  corner           residual    7.500 px  OUTLIER (not used)\n"));
    EXPECT_THAT(text, HasSubstr("  door             residual    0.300 px\n"));
    EXPECT_EQ(text.substr(text.rfind("  written")), "  written: pose.yaml\n");
}

}  // namespace
}  // namespace tirpol::calibration
