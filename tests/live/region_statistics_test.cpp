#include "region_statistics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tirpol/core/error.h"

namespace tirpol::live {
namespace {

DisplayChannel channel(std::string name, std::vector<float> values, std::string units = "") {
    return {std::move(name), std::move(units), std::move(values), {}};
}

TEST(RegionStatistics, AxialMeanOfAnglesEitherSideOfZeroIsZeroNotNinety) {
    // 1° and 179° are polarizations 2° apart; a linear mean calls them 90° ± 126°.
    const DisplayChannel aop = channel("AoP", {1.0f, 179.0f, 1.0f, 179.0f}, "deg");
    const ChannelStatistics s = axial_statistics_deg(aop, 2, {0, 0, 1, 1});
    EXPECT_EQ(s.count, 4u);
    EXPECT_NEAR(std::min(s.mean, 180.0 - s.mean), 0.0, 1e-9);
    // 2θ = ±2°: R̄ = cos 2°, spread = √(−2 ln cos 2°) / 2 in degrees ≈ 1°.
    const double expected = std::sqrt(-2.0 * std::log(std::cos(2.0 * std::numbers::pi / 180.0))) /
                            2.0 * 180.0 / std::numbers::pi;
    EXPECT_NEAR(s.std, expected, 1e-9);
    EXPECT_NEAR(s.std, 1.0, 0.01);
    const ChannelStatistics linear = linear_statistics(aop, 2, {0, 0, 1, 1});
    EXPECT_NEAR(linear.mean, 90.0, 1e-9) << "the linear mean this readout replaced";
}

TEST(RegionStatistics, AxialSpreadMatchesTheLinearOneForASmallSpreadAwayFromTheWrap) {
    std::vector<float> angles;
    for (int i = 0; i < 100; ++i) angles.push_back(60.0f + 0.02f * static_cast<float>(i - 50));
    const DisplayChannel aop = channel("AoP", angles, "deg");
    const ChannelStatistics c = axial_statistics_deg(aop, 100, {0, 0, 99, 0});
    const ChannelStatistics l = linear_statistics(aop, 100, {0, 0, 99, 0});
    EXPECT_NEAR(c.mean, l.mean, 1e-6);
    // √(−2 ln R̄) → the population standard deviation as the spread → 0; the sample one is
    // √(n/(n−1)) larger.
    EXPECT_NEAR(c.std, l.std * std::sqrt(99.0 / 100.0), 1e-3 * l.std);
}

TEST(RegionStatistics, LinearStatisticsLeaveOutFlaggedNonFiniteAndMaskedPixels) {
    DisplayChannel s0 = channel("S0", {1.0f, 2.0f, 3.0f, 1000.0f, NAN, 4.0f}, "counts");
    s0.flags = {kPixelOk, kPixelOk, kPixelOk, kPixelSaturated, kPixelOk, kPixelOk};
    const ChannelStatistics s = linear_statistics(s0, 3, {0, 0, 2, 1});
    EXPECT_EQ(s.count, 4u);
    EXPECT_DOUBLE_EQ(s.mean, 2.5);
    EXPECT_NEAR(s.std, std::sqrt(5.0 / 3.0), 1e-12);
    const std::vector<bool> keep = {true, true, false, true, true, false};
    EXPECT_DOUBLE_EQ(linear_statistics(s0, 3, {0, 0, 2, 1}, &keep).mean, 1.5);
    EXPECT_DOUBLE_EQ(linear_statistics(s0, 3, {1, 0, 1, 0}).mean, 2.0) << "one pixel";
    EXPECT_TRUE(std::isnan(linear_statistics(s0, 3, {1, 0, 1, 0}).std));
}

/// A 64×64 image with a vertical edge at x = 32 from 1000 to 2000, blurred by a box of `width`.
DisplayChannel edge(int blur) {
    std::vector<float> v(64 * 64);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            double sum = 0.0;
            for (int k = -blur; k <= blur; ++k) sum += x + k >= 32 ? 2000.0 : 1000.0;
            v[static_cast<std::size_t>(y * 64 + x)] = static_cast<float>(sum / (2 * blur + 1));
        }
    return channel("S0", v, "counts");
}

TEST(RegionStatistics, GradientEnergyFallsAsTheImageBlurs) {
    const PixelRegion all{0, 0, 63, 63};
    double previous = gradient_energy(edge(0), 64, all);
    // Sharp edge: one step of 1000 per row among 63·64 x- and 64·63 y-differences.
    EXPECT_NEAR(previous, 2.0 * 64.0 * 1000.0 * 1000.0 / (2.0 * 63.0 * 64.0), 1e-6);
    for (const int blur : {1, 2, 4, 8}) {
        const double e = gradient_energy(edge(blur), 64, all);
        EXPECT_LT(e, previous) << "box blur ±" << blur;
        previous = e;
    }
    EXPECT_DOUBLE_EQ(gradient_energy(channel("S0", std::vector<float>(16, 5.0f)), 4, {0, 0, 3, 3}),
                     0.0);
}

TEST(RegionStatistics, GradientEnergyOfARampIsItsSlopeSquared) {
    std::vector<float> v(10 * 10);
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 10; ++x)
            v[static_cast<std::size_t>(y * 10 + x)] = static_cast<float>(3 * x + 4 * y);
    EXPECT_NEAR(gradient_energy(channel("S0", v), 10, {2, 2, 7, 7}), 25.0, 1e-9);
}

TEST(RegionStatistics, TheReadoutMasksAopBelowTheDoLPThresholdAndReportsFocus) {
    DisplayImage cycle;
    cycle.width = 2;
    cycle.height = 2;
    cycle.channels = {channel("DoLP", {0.2f, 0.2f, 0.001f, 0.001f}),
                      channel("AoP", {1.0f, 179.0f, 90.0f, 90.0f}, "deg")};
    DisplayImage live;
    live.width = 2;
    live.height = 2;
    live.channels = {channel("S0", {1.0f, 2.0f, 3.0f, 4.0f}, "counts")};
    live.info["frame_id"] = 7;
    const nlohmann::json j = region_readout(&live, &cycle, {0, 0, 5, 5}, 0.01);
    EXPECT_EQ(j["cycle"]["AoP"]["count"], 2);
    EXPECT_EQ(j["cycle"]["AoP"]["masked"], 2);
    EXPECT_TRUE(j["cycle"]["AoP"]["circular"].get<bool>());
    const double mean = j["cycle"]["AoP"]["mean"];
    EXPECT_NEAR(std::min(mean, 180.0 - mean), 0.0, 1e-9);
    EXPECT_DOUBLE_EQ(j["live"]["S0"]["mean"].get<double>(), 2.5);
    // x differences 1, 1; y differences 2, 2: mean squared 2.5, times 2.
    EXPECT_DOUBLE_EQ(j["focus"]["value"].get<double>(), 5.0);
    EXPECT_EQ(j["focus"]["units"], "(counts/px)²");
    EXPECT_EQ(j["frame_id"], 7);
    // Threshold 0: every finite DoLP counts and the two 90° pixels pull the axial mean.
    EXPECT_EQ(region_readout(nullptr, &cycle, {0, 0, 1, 1}, 0.0)["cycle"]["AoP"]["count"], 4);
}

TEST(RegionStatistics, BadRegionsAndThresholdsAreRefusedByName) {
    DisplayImage live;
    live.width = 2;
    live.height = 2;
    live.channels = {channel("S0", {1.0f, 2.0f, 3.0f, 4.0f}, "counts")};
    EXPECT_THROW(region_readout(&live, nullptr, {1, 0, 0, 1}, 0.0), Error);
    EXPECT_THROW(region_readout(&live, nullptr, {5, 5, 9, 9}, 0.0), Error);
    EXPECT_THROW(region_readout(&live, nullptr, {0, 0, 1, 1}, 1.5), Error);
    EXPECT_THROW(region_readout(&live, nullptr, {0, 0, 1, 1}, NAN), Error);
    try {
        region_readout(&live, nullptr, {0, 0, 1, 1}, -0.1);
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("dolp_min"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace tirpol::live
