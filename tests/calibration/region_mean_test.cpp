// The ROI statistic shared by emissivity extraction and the twin: the mean of the finite pixels of
// a rectangle and its standard error s/√n (sample standard deviation s with n − 1, the textbook
// standard error of the mean), checked on a hand-computed patch.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tirpol/calibration/emissivity_extraction.h"
#include "tirpol/core/error.h"

namespace tirpol::calibration {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

/// A 5×4 image whose 3×2 patch at (1, 1) holds 1…6 and everything else 1000 (must not leak in).
Image patch_image() {
    Image im(5, 4);
    auto& v = im.add_channel("S0", 1000.0f);
    float value = 1.0f;
    for (int y = 1; y < 3; ++y)
        for (int x = 1; x < 4; ++x) v[im.index(x, y)] = value++;
    return im;
}

TEST(RegionMean, MeanAndStandardErrorOfAKnownPatch) {
    // 1…6: mean 3.5, Σ(v − 3.5)² = 17.5, s² = 17.5/5 = 3.5, standard error √(3.5/6).
    const RegionMean r = region_mean(patch_image(), "S0", {1, 1, 3, 2}, "patch");
    EXPECT_EQ(r.n, 6u);
    EXPECT_DOUBLE_EQ(r.mean, 3.5);
    EXPECT_NEAR(r.standard_error, std::sqrt(3.5 / 6.0), 1e-12);
}

TEST(RegionMean, SkipsNonFinitePixels) {
    // Bad pixels are NaN after calibration: 6 → NaN and 5 → +∞ leave 1…4: mean 2.5, s² = 5/3.
    Image im = patch_image();
    im.channel("S0")[im.index(3, 2)] = kNaN;
    im.channel("S0")[im.index(2, 2)] = std::numeric_limits<float>::infinity();
    const RegionMean r = region_mean(im, "S0", {1, 1, 3, 2}, "patch");
    EXPECT_EQ(r.n, 4u);
    EXPECT_DOUBLE_EQ(r.mean, 2.5);
    EXPECT_NEAR(r.standard_error, std::sqrt(5.0 / 3.0 / 4.0), 1e-12);
}

TEST(RegionMean, OnePixelHasNoScatter) {
    const RegionMean r = region_mean(patch_image(), "S0", {2, 1, 1, 1}, "pixel");
    EXPECT_EQ(r.n, 1u);
    EXPECT_DOUBLE_EQ(r.mean, 2.0);
    EXPECT_EQ(r.standard_error, 0.0);
}

TEST(RegionMean, OfAComputedValueSuchAsADifferenceOfImages) {
    // The twin's measured − truth: a − b over the patch is 1…6 − 1 = 0…5, the same scatter.
    const Image a = patch_image();
    Image b(5, 4);
    b.add_channel("S0", 1.0f);
    const auto &ca = a.channel("S0"), &cb = b.channel("S0");
    const RegionMean r = region_mean_of({1, 1, 3, 2}, "twin", "S0", [&](int x, int y) {
        return ca[a.index(x, y)] - cb[b.index(x, y)];
    });
    EXPECT_DOUBLE_EQ(r.mean, 2.5);
    EXPECT_NEAR(r.standard_error, std::sqrt(3.5 / 6.0), 1e-12);
}

TEST(RegionMean, NamesTheRegionWhenNothingIsFiniteOrTheRectangleIsOutside) {
    Image im = patch_image();
    for (float& v : im.channel("S0")) v = kNaN;
    try {
        region_mean(im, "S0", {1, 1, 3, 2}, "panel_a");
        FAIL() << "expected tirpol::Error";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), testing::HasSubstr(
                                  "panel_a: no finite S0 pixel in the rectangle [1, 1, 3, 2]"));
    }
    try {
        region_mean(patch_image(), "S0", {3, 2, 3, 3}, "reflector");
        FAIL() << "expected tirpol::Error";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), testing::HasSubstr(
                                  "reflector: rectangle [3, 2, 3, 3] is outside the 5×4 image"));
    }
}

}  // namespace
}  // namespace tirpol::calibration
