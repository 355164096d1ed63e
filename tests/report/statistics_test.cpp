// Region statistics and the z statistic against values computed by hand, and Immerkær's noise
// estimator against noise of known σ.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "tirpol/report/comparison_report.h"

using namespace tirpol::report;

TEST(ReportStatistics, QuantityStatsMatchHandComputedValues) {
    // Region = pixels 0, 1, 2, 4 (pixel 3 outside, pixel 5 NaN in the simulation).
    const std::vector<float> m{1, 2, 3, 100, 6, 7};
    const std::vector<float> s{2, 2, 1, 0, 3, NAN};
    const std::vector<std::uint8_t> mask{1, 1, 1, 0, 1, 1};
    const QuantityStats st = quantity_stats(m, s, mask);
    // m = {1,2,3,6}: mean 3, population var (4+1+0+9)/4 = 3.5.  s = {2,2,1,3}: mean 2, var
    // (0+0+1+1)/4 = 0.5. d = m − s = {−1, 0, 2, 3}: bias 1, mean square (1+0+4+9)/4 = 3.5.
    EXPECT_EQ(st.pixel_count, 4u);
    EXPECT_DOUBLE_EQ(st.measured_mean, 3.0);
    EXPECT_NEAR(st.measured_std, std::sqrt(3.5), 1e-12);
    EXPECT_DOUBLE_EQ(st.simulated_mean, 2.0);
    EXPECT_NEAR(st.simulated_std, std::sqrt(0.5), 1e-12);
    EXPECT_DOUBLE_EQ(st.bias, 1.0);
    EXPECT_NEAR(st.rmse, std::sqrt(3.5), 1e-12);
}

TEST(ReportStatistics, EmptyRegionGivesZeroCount) {
    const QuantityStats st = quantity_stats({1, 2}, {1, 2}, {0, 0});
    EXPECT_EQ(st.pixel_count, 0u);
    EXPECT_FALSE(masked_mean({1, 2}, {0, 0}).has_value());
    EXPECT_DOUBLE_EQ(*masked_mean({1, NAN, 5}, {1, 1, 1}), 3.0);
}

TEST(ReportStatistics, ZScoresAndTheirSummaryMatchHandValues) {
    // z = (m − s)/√(var_m + var_s): (5−1)/√(3+1) = 2, (0−3)/√(0.5+0.5) = −3, (1−1)/1 =
    // 0, 1.5/√(2+0.25) = 1, zero total variance → NaN, NaN input → NaN.
    const auto z = z_scores({5, 0, 1, 2.5f, 1, NAN}, {1, 3, 1, 1, 1, 0}, {3, 0.5f, 1, 2, 0, 1},
                            {1, 0.5f, 0, 0.25f, 0, 1});
    ASSERT_EQ(z.size(), 6u);
    EXPECT_FLOAT_EQ(z[0], 2.0f);
    EXPECT_FLOAT_EQ(z[1], -3.0f);
    EXPECT_FLOAT_EQ(z[2], 0.0f);
    EXPECT_FLOAT_EQ(z[3], 1.0f);
    EXPECT_TRUE(std::isnan(z[4]));
    EXPECT_TRUE(std::isnan(z[5]));
    const ZStats st = z_stats({2.5f, -3.5f, 0.5f, 1.0f, NAN}, {1, 1, 1, 1, 1});
    EXPECT_EQ(st.pixel_count, 4u);
    EXPECT_DOUBLE_EQ(st.fraction_above_2, 0.5);   // 2.5 and −3.5
    EXPECT_DOUBLE_EQ(st.fraction_above_3, 0.25);  // −3.5
    EXPECT_DOUBLE_EQ(st.mean, 0.125);
    EXPECT_NEAR(st.rms, std::sqrt((6.25 + 12.25 + 0.25 + 1.0) / 4.0), 1e-12);
}

TEST(ReportStatistics, StudentTMapsToTheNormalOfTheSameTailProbability) {
    // Two-sided 5 % and 1 % points of Student's t (NIST/SEMATECH e-Handbook of Statistical Methods,
    // §1.3.6.7.2, table of upper critical values): t(0.975; 4) = 2.776, t(0.995; 10) = 3.169, whose
    // normal equivalents are 1.95996 and 2.57583 (Abramowitz & Stegun, Table 26.1).
    EXPECT_NEAR(normal_equivalent_of_t(2.776, 4.0), 1.95996, 2e-4);
    EXPECT_NEAR(normal_equivalent_of_t(-3.169, 10.0), -2.57583, 2e-4);
    EXPECT_DOUBLE_EQ(normal_equivalent_of_t(1.7, std::numeric_limits<double>::infinity()), 1.7);
    EXPECT_NEAR(normal_equivalent_of_t(1.7, 1e7), 1.7,
                1e-5);  // t → normal for many degrees of freedom
    EXPECT_EQ(normal_equivalent_of_t(0.0, 3.0), 0.0);
}

TEST(ReportStatistics, ZWithAFewSampleVarianceKeepsTheNormalTailFraction) {
    // A render's variance estimated from ν = 4 degrees of freedom (8 spp): the plain ratio has
    // P(|t₄| > 2) = 11.6 % of pixels beyond 2 under noise alone; the dof-aware z must give 4.55 %.
    // Half of the variance is measured (known, ν = ∞), half simulated (ν = 4), as in the digital
    // twin.
    std::mt19937 rng(3);
    std::normal_distribution<double> unit(0.0, 1.0);
    constexpr int kN = 200000, kDof = 4;
    std::vector<float> m(kN), s(kN, 0.0f), vm(kN, 0.5f), vs(kN);
    for (int i = 0; i < kN; ++i) {
        m[i] = static_cast<float>(unit(rng));  // true variance 0.5 + 0.5
        double chi2 = 0.0;
        for (int k = 0; k < kDof; ++k) chi2 += std::pow(unit(rng), 2);
        vs[i] = static_cast<float>(0.5 * chi2 / kDof);
    }
    const std::vector<std::uint8_t> all(kN, 1);
    const ZStats plain = z_stats(z_scores(m, s, vm, vs), all);
    const ZStats aware =
        z_stats(z_scores(m, s, vm, vs, std::numeric_limits<double>::infinity(), kDof), all);
    const double binomial_sd = std::sqrt(0.0455 * 0.9545 / kN);
    EXPECT_GT(plain.fraction_above_2, 0.0455 + 10 * binomial_sd);
    // Welch–Satterthwaite is an approximation: within 0.5 % of the nominal tail.
    EXPECT_NEAR(aware.fraction_above_2, 0.0455, 0.005);
    EXPECT_TRUE(consistent_with_noise(
        z_stats(z_scores({m.begin(), m.begin() + 2000}, {s.begin(), s.begin() + 2000},
                         {vm.begin(), vm.begin() + 2000}, {vs.begin(), vs.begin() + 2000},
                         std::numeric_limits<double>::infinity(), kDof),
                std::vector<std::uint8_t>(2000, 1))));
}

TEST(ReportStatistics, NormalTailConstantsMatchErfc) {
    // P(|z| > k) = erfc(k/√2) (Abramowitz & Stegun 26.2.2 with 7.1.2).
    EXPECT_NEAR(kNormalTailAbove2, std::erfc(2.0 / std::sqrt(2.0)), 1e-12);
    EXPECT_NEAR(kNormalTailAbove3, std::erfc(3.0 / std::sqrt(2.0)), 1e-12);
}

TEST(ReportStatistics, ConsistencyVerdictUsesBinomialTolerance) {
    ZStats z;
    z.pixel_count = 10000;  // 3 binomial σ of 4.55 % over 10⁴ pixels = 0.625 %
    z.fraction_above_2 = 0.051;
    EXPECT_TRUE(consistent_with_noise(z));
    z.fraction_above_2 = 0.053;
    EXPECT_FALSE(consistent_with_noise(z));
}

TEST(ReportStatistics, ImmerkaerEstimatesKnownNoiseOnASmoothImage) {
    // White Gaussian noise of σ = 0.2 on a plane: Immerkær (1996) is unbiased for white noise and
    // blind to linear trends (the kernel annihilates planes).
    const int w = 200, h = 150;
    std::mt19937 rng(3);
    std::normal_distribution<double> n(0.0, 0.2);
    std::vector<float> data(static_cast<std::size_t>(w * h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            data[static_cast<std::size_t>(y * w + x)] =
                static_cast<float>(20.0 + 0.05 * x - 0.03 * y + n(rng));
    EXPECT_NEAR(immerkaer_noise_sigma(data, w, h), 0.2, 0.2 * 0.03);
}
