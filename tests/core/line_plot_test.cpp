// Line plots: a readable PNG of the requested size, 1-2-5 ticks, and clear errors.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "test_support.h"
#include "tirpol/core/error.h"
#include "tirpol/core/quicklook.h"

namespace tirpol {
namespace {

// Width and height from the PNG IHDR chunk (PNG spec, ISO/IEC 15948 §11.2.2: big-endian at bytes
// 16–23).
std::pair<int, int> png_size(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    unsigned char b[24] = {};
    in.read(reinterpret_cast<char*>(b), 24);
    EXPECT_EQ(b[1], 'P');
    EXPECT_EQ(b[2], 'N');
    EXPECT_EQ(b[3], 'G');
    auto be = [&](int o) { return (b[o] << 24) | (b[o + 1] << 16) | (b[o + 2] << 8) | b[o + 3]; };
    return {be(16), be(20)};
}

TEST(LinePlot, WritesPngOfRequestedSize) {
    test::TempDir dir;
    PlotSeries s{"e_s0", {0, 30, 60, 90}, {0.95, 0.94, 0.9, 0.5}};
    PlotSeries t{"e_s1", {0, 30, 60, 90}, {0.0, -0.01, -0.05, -0.1}, {214, 39, 40}, true};
    LinePlotOptions o;
    o.title = "test";
    o.x_label = "angle (deg)";
    o.y_label = "emissivity";
    o.width = 640;
    o.height = 480;
    write_line_plot(dir / "p.png", {s, t}, o);
    EXPECT_EQ(png_size(dir / "p.png"), std::make_pair(640, 480));
}

TEST(LinePlot, RejectsBadInput) {
    test::TempDir dir;
    EXPECT_THROW(write_line_plot(dir / "p.png", {}, {}), Error);
    PlotSeries bad{"x", {0, 1}, {1}};
    try {
        write_line_plot(dir / "p.png", {bad}, {});
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), ::testing::HasSubstr("2 x values but 1 y values"));
    }
}

TEST(LinePlot, NiceTicksAreOneTwoFiveMultiples) {
    EXPECT_EQ(nice_ticks(0.0, 90.0, 9),
              (std::vector<double>{0, 10, 20, 30, 40, 50, 60, 70, 80, 90}));
    const auto t = nice_ticks(-0.13, 1.0, 6);
    ASSERT_GE(t.size(), 2u);
    EXPECT_NEAR(t[1] - t[0], 0.2, 1e-12);
    EXPECT_NEAR(t.front(), 0.0, 1e-12);
}

}  // namespace
}  // namespace tirpol
