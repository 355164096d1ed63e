// Region masks: objects, sectors around the object's centre (0° = image right, 90° = image top, the
// Stokes reference of docs/conventions.md) and polygons.

#include <gtest/gtest.h>

#include "tirpol/sweep/sweep_run.h"

namespace tirpol::sweep {
namespace {

/// A 21×21 image whose object 1 is a disk of radius 8 px centred on pixel (10, 10); object 0
/// elsewhere.
Image disk_image() {
    Image image(21, 21);
    auto& id = image.add_channel("object_id", 0.0f);
    for (int y = 0; y < 21; ++y)
        for (int x = 0; x < 21; ++x)
            if ((x - 10) * (x - 10) + (y - 10) * (y - 10) <= 64) id[image.index(x, y)] = 1.0f;
    return image;
}

TEST(RegionPixels, OpposedSectorPairsSplitAnObjectIntoClockQuadrants) {
    const Image image = disk_image();
    const std::vector<std::string> objects = {"snow", "ball"};
    const RegionSpec all{"ball", "ball", {}, std::nullopt, "test"};
    const RegionSpec sides{"sides", "ball", {{-45, 45}, {135, 225}}, std::nullopt, "test"};
    const RegionSpec top_bottom{
        "top_bottom", "ball", {{45, 135}, {225, 315}}, std::nullopt, "test"};
    const RegionSpec top{"top", "ball", {{46, 134}}, std::nullopt, "test"};
    const auto m_all = region_pixels(image, objects, all),
               m_sides = region_pixels(image, objects, sides),
               m_tb = region_pixels(image, objects, top_bottom),
               m_top = region_pixels(image, objects, top);
    std::size_t n_all = 0, n_sides = 0, n_tb = 0;
    for (std::size_t i = 0; i < m_all.size(); ++i) {
        n_all += m_all[i], n_sides += m_sides[i], n_tb += m_tb[i];
        if (!m_all[i]) {
            EXPECT_EQ(m_sides[i] + m_tb[i], 0) << "sectors stay inside the object";
        }
    }
    // The diagonals (|dx| = |dy|) belong to both closed sectors; every other object pixel to
    // exactly one. A disk is symmetric under a 90° turn; only its centre pixel (angle 0 by atan2(0,
    // 0)) is a side pixel.
    EXPECT_EQ(n_sides, n_tb + 1);
    EXPECT_GE(n_sides + n_tb, n_all);
    EXPECT_EQ(m_sides[image.index(18, 10)], 1) << "3 o'clock";
    EXPECT_EQ(m_sides[image.index(2, 10)], 1) << "9 o'clock";
    EXPECT_EQ(m_tb[image.index(10, 2)], 1) << "12 o'clock";
    EXPECT_EQ(m_top[image.index(10, 2)], 1)
        << "90° is the top of the image (row 2 is above the centre)";
    EXPECT_EQ(m_top[image.index(10, 18)], 0) << "6 o'clock is not in the top sector";
    EXPECT_EQ(m_all[image.index(0, 0)], 0) << "a corner is not the ball";
}

TEST(RegionPixels, PolygonIsIntersectedWithTheObject) {
    const Image image = disk_image();
    report::Region left{"left", {{0, 0}, {10, 0}, {10, 20}, {0, 20}}, "test"};
    const RegionSpec left_of_ball{"left", "ball", {}, left, "test"};
    const auto mask = region_pixels(image, {"snow", "ball"}, left_of_ball);
    EXPECT_EQ(mask[image.index(4, 10)], 1);
    EXPECT_EQ(mask[image.index(16, 10)], 0) << "right of the polygon";
    EXPECT_EQ(mask[image.index(0, 0)], 0) << "inside the polygon but not the ball";
}

}  // namespace
}  // namespace tirpol::sweep
