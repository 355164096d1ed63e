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
#include "tirpol/report/verdict.h"

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

/// Over `seeds` independent 5×5 images of one-dof variance estimates v̂ = σ²·χ²₁ (a render's at two
/// replicates) around the true variances `sigma2`, the centre pixel's pooled variance: its scatter
/// as degrees of freedom, 2·mean²/variance (a scaled χ²_ν has variance 2·mean²/ν), and the mean
/// of the dof the pooling states.
struct PooledScatter {
    double scatter_dof = 0.0, stated_dof = 0.0, satterthwaite_true_dof = 0.0;
};
PooledScatter pooled_scatter_over_seeds(const std::vector<double>& sigma2, int seeds) {
    const int w = 5, h = 5;
    std::mt19937 rng(17);
    std::normal_distribution<double> normal(0.0, 1.0);
    std::vector<float> variance(w * h);
    double sum = 0.0, sum_sq = 0.0, stated = 0.0;
    for (int s = 0; s < seeds; ++s) {
        for (int i = 0; i < w * h; ++i) {
            const double z = normal(rng);
            variance[i] = static_cast<float>(sigma2[i] * z * z);
        }
        const PooledVariance p = pool_variance(variance, {}, w, h, kVariancePoolRadiusPx, 1.0);
        const double v = p.variance[2 * w + 2];
        sum += v, sum_sq += v * v, stated += p.dof[2 * w + 2];
    }
    const double mean = sum / seeds, var = sum_sq / seeds - mean * mean;
    double s1 = 0.0, s2 = 0.0;
    for (double x : sigma2) s1 += x, s2 += x * x;
    return {2.0 * mean * mean / var, stated / seeds, s1 * s1 / s2};
}

TEST(PooledVariance, TheStatedDofMatchesThePooledEstimatesScatterOverSeeds) {
    // 20000 seeds: the scatter's dof has a relative standard error of about √(2.6/20000) = 1.1 %
    // (the sample variance of a near-χ²₂₂ quantity), so it is held to 5 % of Satterthwaite's on
    // the true variances. The stated dof is itself estimated from one-dof variances and held to
    // ≤ ν·n, so its mean over seeds may sit a few per cent off the scatter (23.2 against 25.0 at
    // equal variances, measured): 10 %.
    constexpr int kSeeds = 20000;
    // Equal variances: ν·n = 25, what every pixel pooled with its 24 neighbours states.
    const PooledScatter equal = pooled_scatter_over_seeds(std::vector<double>(25, 1.0), kSeeds);
    // A variance rising ×4 across the window, as over a surface turning towards the sky: the
    // Satterthwaite dof is 21.2, and ν·n = 25 would be 18 % high.
    std::vector<double> ramp(25);
    for (int i = 0; i < 25; ++i) ramp[i] = 1.0 + 3.0 * (i % 5) / 4.0;
    const PooledScatter rising = pooled_scatter_over_seeds(ramp, kSeeds);
    for (const auto& [name, c] : {std::pair{"equal", equal}, std::pair{"rising ×4", rising}}) {
        std::printf("%s: scatter %.2f dof, stated %.2f (mean), Satterthwaite on the truth %.2f\n",
                    name, c.scatter_dof, c.stated_dof, c.satterthwaite_true_dof);
        EXPECT_NEAR(c.scatter_dof, c.satterthwaite_true_dof, 0.05 * c.satterthwaite_true_dof)
            << name;
        EXPECT_NEAR(c.stated_dof, c.scatter_dof, 0.10 * c.scatter_dof) << name;
    }
    EXPECT_GT(25.0 - rising.scatter_dof, 0.10 * rising.scatter_dof) << "ν·n would have passed";
    // Two levels ×9 apart on one surface (the edge of a reflection): the estimates see the step
    // only through one-dof noise, so the stated dof stays above the scatter's, but by less than
    // half of what ν·n = 25 would overstate.
    std::vector<double> step(25);
    for (int i = 0; i < 25; ++i) step[i] = i % 5 < 2 ? 1.0 : 9.0;
    const PooledScatter edge = pooled_scatter_over_seeds(step, kSeeds);
    std::printf("step ×9: scatter %.2f dof, stated %.2f (mean), Satterthwaite on the truth %.2f\n",
                edge.scatter_dof, edge.stated_dof, edge.satterthwaite_true_dof);
    EXPECT_NEAR(edge.scatter_dof, edge.satterthwaite_true_dof, 0.05 * edge.satterthwaite_true_dof);
    EXPECT_GE(edge.stated_dof, edge.scatter_dof * 0.95);
    EXPECT_LT(edge.stated_dof - edge.scatter_dof, 0.5 * (25.0 - edge.scatter_dof));
}

TEST(PooledVariance, SatterthwaiteDofIsBetweenOnePixelsAndAllPixelsDof) {
    // Equal estimates: ν·n exactly (clamped from (ν + 2)·n − 2).
    EXPECT_DOUBLE_EQ(satterthwaite_pooled_dof(25.0, 25.0, 25, 1.0), 25.0);
    // All the variance in one pixel: one pixel's dof.
    EXPECT_DOUBLE_EQ(satterthwaite_pooled_dof(7.0, 49.0, 25, 1.0), 1.0);
    // Every estimate 0 (a pixel with no Monte Carlo noise): nothing to weigh, ν·n.
    EXPECT_DOUBLE_EQ(satterthwaite_pooled_dof(0.0, 0.0, 9, 2.0), 18.0);
    // Between: ten pixels at 1 and two at 10, ν = 1: 3·30²/210 − 2 = 10.857 of at most 12.
    const double sum = 10.0 + 2.0 * 10.0, squares = 10.0 + 2.0 * 100.0;
    EXPECT_DOUBLE_EQ(satterthwaite_pooled_dof(sum, squares, 12, 1.0),
                     3.0 * sum * sum / squares - 2.0);
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
