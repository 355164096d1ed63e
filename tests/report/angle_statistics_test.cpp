// AoP statistics as axial (mod 180°) quantities over significantly polarized pixels.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "tirpol/report/comparison_report.h"

using namespace tirpol::report;

namespace {
constexpr double kRad = std::numbers::pi / 180.0;

struct Planes {
    std::vector<float> s1, s2, var;
};
// Linear polarization of magnitude p at angle aop_deg: S1 = p cos 2θ, S2 = p sin 2θ.
void push(Planes& planes, double p, double aop_deg, float var) {
    planes.s1.push_back(static_cast<float>(p * std::cos(2.0 * aop_deg * kRad)));
    planes.s2.push_back(static_cast<float>(p * std::sin(2.0 * aop_deg * kRad)));
    planes.var.push_back(var);
}
AopStats stats(const Planes& m, const Planes& s) {
    return aop_stats({m.s1, m.s2, m.var, m.var}, {s.s1, s.s2, s.var, s.var},
                     std::vector<std::uint8_t>(m.s1.size(), 1));
}
}  // namespace

TEST(ReportAngleStatistics, MeansAcrossTheWrapAreNearTheWrapNotAt90Degrees) {
    // Measured 179°, simulated 1°: the same axis 2° apart. A linear mean of 179 and 1 would say
    // 90°.
    Planes m, s;
    for (int i = 0; i < 100; ++i) {
        push(m, 1.0, 179.0, 1e-4f);
        push(s, 1.0, 1.0, 1e-4f);
    }
    const AopStats a = stats(m, s);
    EXPECT_EQ(a.pixel_count, 100u);
    EXPECT_NEAR(a.measured_mean_deg, 179.0, 1e-3);
    EXPECT_NEAR(a.simulated_mean_deg, 1.0, 1e-3);
    EXPECT_NEAR(a.difference_mean_deg, -2.0, 1e-3);
    EXPECT_NEAR(a.difference_std_deg, 0.0, 1e-2);
}

TEST(ReportAngleStatistics, CircularStdOfAlternatingDifferencesMatchesMardiaJupp) {
    // Differences ±5°: doubled ±10°, mean resultant length R = cos 10°, axial circular std
    // ½√(−2 ln cos 10°) rad = 5.0126° (Mardia & Jupp eq. 2.3.11, halved for axial data).
    Planes m, s;
    for (int i = 0; i < 200; ++i) {
        push(m, 0.5, 40.0 + (i % 2 ? 5.0 : -5.0), 1e-4f);
        push(s, 0.5, 40.0, 1e-4f);
    }
    const AopStats a = stats(m, s);
    EXPECT_NEAR(a.difference_mean_deg, 0.0, 1e-3);
    EXPECT_NEAR(a.difference_std_deg, 5.0126, 2e-3);
    EXPECT_NEAR(a.measured_mean_deg, 40.0, 1e-3);
}

TEST(ReportAngleStatistics, UnpolarizedPixelsAreLeftOut) {
    // 300 pixels polarized at 60° (|P| = 1, σ = 0.01) agree exactly; 700 pixels are noise only
    // (|P| ~ σ) with random angles. Only the polarized pixels count, so the difference stays 0.
    std::mt19937 rng(3);
    std::normal_distribution<double> noise(0.0, 0.01);
    Planes m, s;
    for (int i = 0; i < 300; ++i) {
        push(m, 1.0, 60.0, 1e-4f);
        push(s, 1.0, 60.0, 1e-4f);
    }
    for (int i = 0; i < 700; ++i) {
        m.s1.push_back(static_cast<float>(noise(rng)));
        m.s2.push_back(static_cast<float>(noise(rng)));
        m.var.push_back(1e-4f);
        s.s1.push_back(static_cast<float>(noise(rng)));
        s.s2.push_back(static_cast<float>(noise(rng)));
        s.var.push_back(1e-4f);
    }
    const AopStats a = stats(m, s);
    EXPECT_EQ(a.region_pixel_count, 1000u);
    // A noise-only pixel passes 3σ in both images with probability (e^{−9/2})² ≈ 1.2e-4.
    EXPECT_LE(a.pixel_count, 302u);
    EXPECT_GE(a.pixel_count, 300u);
    EXPECT_NEAR(a.difference_mean_deg, 0.0, 0.5);
    EXPECT_NEAR(a.measured_mean_deg, 60.0, 0.5);
}
