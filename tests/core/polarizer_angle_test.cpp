// Polarizer angle keys (core/polarizer_angle.h): the one rule for "the same nominal angle", its
// channel-name tag, and the signed stage-angle difference.

#include <gtest/gtest.h>

#include "tirpol/core/stokes.h"

namespace tirpol {
namespace {

TEST(PolarizerAngle, SameAngleToTheHundredthOfADegree) {
    EXPECT_TRUE(same_polarizer_angle(45, 45.0));
    EXPECT_TRUE(
        same_polarizer_angle(45.0, static_cast<float>(45.0 + 1e-5)));  // through a float in a file
    EXPECT_TRUE(same_polarizer_angle(22.5, 22.504));
    EXPECT_FALSE(same_polarizer_angle(22.5, 22.51));
    EXPECT_FALSE(same_polarizer_angle(0.0, 180.0));  // different positions of the mount
    EXPECT_EQ(polarizer_angle_key(135.0), 13500);
    EXPECT_EQ(polarizer_angle_key(-10.0), -1000);
    EXPECT_DOUBLE_EQ(polarizer_angle_deg(polarizer_angle_key(112.5)), 112.5);
}

TEST(PolarizerAngle, TagIsTheSameForEveryWayOfWritingAnAngle) {
    EXPECT_EQ(polarizer_angle_tag(0.0), "0");
    EXPECT_EQ(polarizer_angle_tag(45), "45");
    EXPECT_EQ(polarizer_angle_tag(45.0000001), "45");
    EXPECT_EQ(polarizer_angle_tag(22.5), "22p5");
    EXPECT_EQ(polarizer_angle_tag(-10.0), "-10");
}

TEST(PolarizerAngle, DifferenceIsTheShortestSignedTurn) {
    EXPECT_DOUBLE_EQ(angle_difference_deg(359.0, 1.0), -2.0);
    EXPECT_DOUBLE_EQ(angle_difference_deg(1.0, 359.0), 2.0);
    EXPECT_DOUBLE_EQ(angle_difference_deg(90.0, -270.0), 0.0);
    EXPECT_DOUBLE_EQ(angle_difference_deg(180.0, 0.0), -180.0);  // [−180, 180)
    EXPECT_DOUBLE_EQ(wrap_degrees(-30.0), 330.0);
    EXPECT_DOUBLE_EQ(wrap_degrees(720.0), 0.0);
}

}  // namespace
}  // namespace tirpol
