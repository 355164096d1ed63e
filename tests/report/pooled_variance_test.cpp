// Per-pixel use of a variance with few degrees of freedom (a render at the default two replicates:
// one dof per pixel): pooled over each pixel's neighbourhood on the same surface, the z of a
// correct simulation is again standard normal per pixel, where one pixel's own estimate gives
// Student's t₁ (|t₁| > 5 in 12.6 % of pixels: P = 1 − (2/π)·atan 5).

#include "pooled_variance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "synthetic_pair.h"
#include "tirpol/report/comparison_report.h"
#include "tirpol/report/mean_difference_test.h"
#include "tirpol/report/statistics.h"

namespace tirpol::report {
namespace {

TEST(PooledVariance, MeansOverTheSameSurfaceOnlyWithDofPerPixelPooled) {
    // 8×6, left half variance 1 (label 0), right half 4 (label 1), one NaN variance.
    const int w = 8, h = 6;
    std::vector<float> variance(w * h), label(w * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            variance[y * w + x] = x < 4 ? 1.0f : 4.0f;
            label[y * w + x] = x < 4 ? 0.0f : 1.0f;
        }
    variance[2 * w + 5] = std::numeric_limits<float>::quiet_NaN();
    const PooledVariance p = pool_variance(variance, {&label}, w, h, 2, 1.0);
    // Interior of each half: the half's own variance exactly, never mixed across the edge.
    EXPECT_FLOAT_EQ(p.variance[2 * w + 3], 1.0f);
    EXPECT_FLOAT_EQ(p.variance[2 * w + 4], 4.0f);
    // Pixel (3, 2): its 5×5 window holds 5 rows × columns 1..3 of label 0 = 15 pixels.
    EXPECT_FLOAT_EQ(p.dof[2 * w + 3], 15.0f);
    // Pixel (4, 2): 5 rows × columns 4..6 of label 1, less the NaN at (5, 2) = 14.
    EXPECT_FLOAT_EQ(p.dof[2 * w + 4], 14.0f);
    // Corner (0, 0): 3 × 3 pixels, 2 dof each.
    EXPECT_FLOAT_EQ(pool_variance(variance, {&label}, w, h, 2, 2.0).dof[0], 18.0f);
    // The NaN pixel itself gets its neighbours' variance.
    EXPECT_FLOAT_EQ(p.variance[2 * w + 5], 4.0f);
}

TEST(PooledVariance, PooledOneDofVariancesGiveNormalPerPixelZ) {
    // Each pixel: a mean of R = 2 replicate means m_r ~ N(0, 2σ²), so Var(mean) = σ², and the
    // renderer's estimate Σ(m_r − m̄)²/(R(R − 1)) = (m₁ − m₂)²/4, unbiased with one dof. σ varies
    // smoothly over the image (×1 to ×2), as a render's does over a surface.
    const int w = 160, h = 120;
    std::mt19937 rng(5);
    std::normal_distribution<double> normal(0.0, 1.0);
    std::vector<float> measured(w * h, 0.0f), simulated(w * h), variance(w * h), zero(w * h, 0.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const double sigma = 0.01 * (1.0 + static_cast<double>(x) / w);
            const double m1 = std::sqrt(2.0) * sigma * normal(rng),
                         m2 = std::sqrt(2.0) * sigma * normal(rng);
            simulated[y * w + x] = static_cast<float>(0.5 * (m1 + m2));
            variance[y * w + x] = static_cast<float>((m1 - m2) * (m1 - m2) / 4.0);
        }
    const auto tail_fraction = [](const std::vector<float>& z, double beyond) {
        std::size_t n = 0, count = 0;
        for (float v : z)
            if (std::isfinite(v)) ++n, count += std::abs(v) > beyond ? 1 : 0;
        return static_cast<double>(count) / static_cast<double>(n);
    };
    const std::vector<std::uint8_t> all(w * h, 1);
    // One pixel's own variance, taken as exact: Student's t₁, |z| > 5 in 12.6 % of pixels.
    const auto raw = z_scores(measured, simulated, zero, variance);
    const double raw_beyond5 = tail_fraction(raw, 5.0);
    std::printf("own variance as exact: |z| > 5 in %.2f %% (t1: 12.57 %%)\n", 100.0 * raw_beyond5);
    EXPECT_GT(raw_beyond5, 0.10);
    // Pooled over 5×5 (ν = 25 inside): normal-equivalent z standard normal.
    const PooledVariance pooled = pool_variance(variance, {}, w, h, kVariancePoolRadiusPx, 1.0);
    const auto z = z_scores(measured, simulated, zero, pooled.variance, kInfiniteDof, pooled.dof);
    const double beyond3 = tail_fraction(z, 3.0), beyond5 = tail_fraction(z, 5.0);
    const SigmaDiagnostic d = sigma_diagnostic(z, all);
    std::printf(
        "pooled: |z| > 3 in %.3f %% (normal 0.270 %%), |z| > 5 in %.4f %%, var z %.3f ± %.3f\n",
        100.0 * beyond3, 100.0 * beyond5, d.z_variance, d.z_variance_sigma);
    // n = 19200: the count beyond 3 has mean 51.8, sd 7.2; allow 5 sd. The project's |z| > 5 < 0.1
    // %.
    const double n = static_cast<double>(w * h), expected3 = n * kNormalTailAbove3;
    EXPECT_LT(std::abs(beyond3 * n - expected3), 5.0 * std::sqrt(expected3));
    EXPECT_LT(beyond5, 1e-3);
    EXPECT_EQ(d.verdict, SigmaCheck::Plausible);
}

TEST(PooledVariance, TheReportPoolsARendersFewDofVarianceForItsZMaps) {
    // The synthetic pair with the simulation's variance stated at one dof per pixel (a render at
    // two replicates): the report says it pools, and its z of a correct simulation scatter as a
    // unit normal in every region (the σ diagnostic is plausible).
    auto pair = test::make_synthetic_pair({});
    pair.simulated.attributes()["variance_dof"] = 1;
    CompareOptions options;
    options.registration = RegistrationMethod::None;
    const CompareResult r = compare(pair.measured, pair.simulated, options).result;
    for (const Quantity q : kZQuantities) {
        EXPECT_EQ(r.noise[q].simulated_dof, 1.0) << quantity_name(q);
        EXPECT_NE(r.noise[q].simulated.find("5×5 neighbourhood on the same surface"),
                  std::string::npos)
            << r.noise[q].simulated;
    }
    for (const auto& region : r.regions)
        for (const Quantity q : kZQuantities)
            EXPECT_EQ(region.verdicts[q].sigma.verdict, SigmaCheck::Plausible)
                << region.name << " " << quantity_name(q);
}

}  // namespace
}  // namespace tirpol::report
