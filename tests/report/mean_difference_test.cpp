// The region-mean agreement test and the per-pixel σ diagnostic (mean_difference_test.h) on
// synthetic regions of known noise: Student-t quantiles against published tables,
// Welch–Satterthwaite degrees of freedom, a false-alarm rate near the design's α over many
// noise-only regions (with estimated render variances of few dof and a calibration error common to
// each region), and a detection rate near the stated power for a bias equal to the stated
// detectable bias.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "tirpol/report/comparison_report.h"
#include "tirpol/report/verdict.h"

using namespace tirpol::report;

namespace {

// Binomial standard deviation of a rate p over n trials.
double binomial_sd(double p, int n) { return std::sqrt(p * (1.0 - p) / n); }

// One synthetic region: measured = truth + temporal noise (σ_m exact, per pixel) + a calibration
// offset common to the region (σ_c); simulated = truth + Monte Carlo noise whose variance is
// estimated from `replicates` independent replicates per pixel (dof replicates − 1), as the
// renderer does.
struct SyntheticRegion {
    std::vector<float> measured, simulated, var_measured, var_simulated;
    std::vector<std::uint8_t> mask;
};

SyntheticRegion synthetic_region(std::mt19937_64& rng, int n, double sigma_m, double sigma_s,
                                 double sigma_common, int replicates, double bias) {
    std::normal_distribution<double> normal(0.0, 1.0);
    SyntheticRegion r;
    const double offset = sigma_common * normal(rng);
    for (int i = 0; i < n; ++i) {
        const double truth = 30.0 + 0.01 * i;
        r.measured.push_back(static_cast<float>(truth + bias + offset + sigma_m * normal(rng)));
        // The replicate mean has σ_s; each replicate σ_s·√R; the variance of the mean is estimated
        // from the replicates' sample variance / R.
        double sum = 0.0, sum2 = 0.0;
        const double replicate_sigma = sigma_s * std::sqrt(static_cast<double>(replicates));
        for (int k = 0; k < replicates; ++k) {
            const double x = truth + replicate_sigma * normal(rng);
            sum += x;
            sum2 += x * x;
        }
        const double mean = sum / replicates;
        const double sample_var = (sum2 - replicates * mean * mean) / (replicates - 1);
        r.simulated.push_back(static_cast<float>(mean));
        r.var_simulated.push_back(static_cast<float>(sample_var / replicates));
        r.var_measured.push_back(static_cast<float>(sigma_m * sigma_m));
        r.mask.push_back(1);
    }
    return r;
}

MeanDifferenceTest run_test(const SyntheticRegion& r, int replicates, double sigma_common,
                            const TestDesign& design) {
    MeanDifferenceInputs in;
    in.measured = &r.measured;
    in.simulated = &r.simulated;
    in.measured_variance = &r.var_measured;
    in.simulated_variance = &r.var_simulated;
    in.mask = &r.mask;
    in.simulated_dof = replicates - 1;
    in.measured_common.sigma = sigma_common;
    return test_mean_difference(in, design);
}

}  // namespace

TEST(MeanDifferenceTest, StudentTQuantilesMatchTheNistTable) {
    // NIST/SEMATECH e-Handbook of Statistical Methods §1.3.6.7.2 (upper critical values of t).
    EXPECT_NEAR(student_t_quantile(0.975, 10), 2.228, 1e-3);
    EXPECT_NEAR(student_t_quantile(0.975, 5), 2.571, 1e-3);
    EXPECT_NEAR(student_t_quantile(0.995, 7), 3.499, 1e-3);
    EXPECT_NEAR(student_t_quantile(0.90, 20), 1.325, 1e-3);
    EXPECT_NEAR(student_t_quantile(0.80, 10), 0.879, 1e-3);
    EXPECT_NEAR(student_t_quantile(0.025, 10), -2.228, 1e-3);
    EXPECT_NEAR(student_t_quantile(0.975, kInfiniteDof), 1.959964, 1e-6);
    EXPECT_NEAR(student_t_two_sided_tail(2.228, 10), 0.05, 1e-4);
}

TEST(MeanDifferenceTest, WelchSatterthwaiteDegreesOfFreedom) {
    // GUM JCGM 100:2008 eq G.2b: ν = σ⁴/Σ(σ_i⁴/ν_i). Equal σ, one with ν = 10, one exact: ν =
    // 4/(1/10) = 40.
    const UncertaintyComponent c = combine({{1.0, 10.0}, {1.0, kInfiniteDof}});
    EXPECT_NEAR(c.sigma, std::sqrt(2.0), 1e-12);
    EXPECT_NEAR(c.dof, 40.0, 1e-9);
    EXPECT_TRUE(std::isinf(combine({{1.0, kInfiniteDof}, {0.5, kInfiniteDof}}).dof));
    // n pixels of equal variance v, each with ν: σ_mean = √(v/n), ν_mean = n·ν.
    const std::vector<float> v(25, 4.0f);
    const std::vector<std::uint8_t> mask(25, 1);
    const UncertaintyComponent m = mean_of_independent(v, mask, 7.0);
    EXPECT_NEAR(m.sigma, std::sqrt(4.0 / 25.0), 1e-9);
    EXPECT_NEAR(m.dof, 25.0 * 7.0, 1e-6);
}

TEST(MeanDifferenceTest, FalseAlarmRateOverManyNoiseOnlyRegionsIsAlpha) {
    // 4000 regions of 60 pixels; the render's variance from 8 replicates (ν = 7 per pixel); a
    // common calibration offset of the size of the independent noise of the mean. Every quantity
    // tested at α_q = 1 − 0.95^(1/3) = 1.70 %: the rate of "exceeds noise" must be α_q within 4
    // binomial σ.
    std::mt19937_64 rng(2026);
    const TestDesign design;
    const int regions = 4000, n = 60, replicates = 8;
    const double sigma_m = 0.02, sigma_s = 0.05,
                 sigma_common = std::hypot(sigma_m, sigma_s) / std::sqrt(60.0);
    int alarms = 0, alarms_without_common = 0, sigma_flags = 0;
    for (int k = 0; k < regions; ++k) {
        const SyntheticRegion r =
            synthetic_region(rng, n, sigma_m, sigma_s, sigma_common, replicates, 0.0);
        alarms += run_test(r, replicates, sigma_common, design).verdict == Agreement::ExceedsNoise;
        alarms_without_common +=
            run_test(r, replicates, 0.0, design).verdict == Agreement::ExceedsNoise;
        std::vector<float> z = z_scores(r.measured, r.simulated, r.var_measured, r.var_simulated,
                                        kInfiniteDof, replicates - 1.0);
        sigma_flags += sigma_diagnostic(z, r.mask).verdict != SigmaCheck::Plausible;
    }
    const double alpha = design.false_alarm_per_quantity();
    EXPECT_NEAR(alpha, 0.016952, 1e-5);
    const double rate = static_cast<double>(alarms) / regions;
    EXPECT_NEAR(rate, alpha, 4.0 * binomial_sd(alpha, regions)) << alarms << " of " << regions;
    // Leaving out the error common to the region's pixels false-alarms far more often (here the
    // common σ equals the independent one, so |d|/σ_independent is √2 too large: P(|N| > 2.39·0.71)
    // ≈ 9 %).
    EXPECT_GT(static_cast<double>(alarms_without_common) / regions, 3.0 * alpha)
        << alarms_without_common;
    // The σ diagnostic (3 sampling σ and a factor 1.25) rarely fires on honest variances.
    EXPECT_LT(static_cast<double>(sigma_flags) / regions, 0.01) << sigma_flags;
}

TEST(MeanDifferenceTest, DetectionRateAtTheStatedDetectableBiasIsThePower) {
    // A bias equal to (t_{1−α_q/2,ν} + t_{0.8,ν})·σ_mean is detected in 80 % of regions.
    std::mt19937_64 rng(7);
    const TestDesign design;
    const int regions = 3000, n = 40, replicates = 8;
    const double sigma_m = 0.03, sigma_s = 0.04;
    const double sigma_mean = std::hypot(sigma_m, sigma_s) / std::sqrt(static_cast<double>(n));
    // The expected detectable bias at the true σ (the test computes it from the estimated σ).
    const SyntheticRegion probe = synthetic_region(rng, n, sigma_m, sigma_s, 0.0, replicates, 0.0);
    const MeanDifferenceTest p = run_test(probe, replicates, 0.0, design);
    const double bias =
        (p.critical_t + student_t_quantile(design.power, p.combined.dof)) * sigma_mean;
    int detected = 0;
    double stated = 0.0;
    for (int k = 0; k < regions; ++k) {
        const SyntheticRegion r = synthetic_region(rng, n, sigma_m, sigma_s, 0.0, replicates, bias);
        const MeanDifferenceTest t = run_test(r, replicates, 0.0, design);
        detected += t.verdict == Agreement::ExceedsNoise;
        stated += t.detectable_bias / regions;
    }
    EXPECT_NEAR(static_cast<double>(detected) / regions, design.power,
                4.0 * binomial_sd(design.power, regions))
        << detected << " of " << regions;
    EXPECT_NEAR(stated, bias,
                0.03 * bias);  // the stated figure is the true one within its estimation error
}

TEST(MeanDifferenceTest, SigmaDiagnosticReadsTheScatterOfZ) {
    std::mt19937_64 rng(11);
    std::normal_distribution<double> normal(0.0, 1.0);
    const std::vector<std::uint8_t> mask(2000, 1);
    std::vector<float> z(2000), half(2000), twice(2000), shifted(2000);
    for (std::size_t i = 0; i < z.size(); ++i) {
        z[i] = static_cast<float>(normal(rng));
        half[i] = 0.5f * z[i];
        twice[i] = 2.0f * z[i];
        shifted[i] =
            z[i] + 3.0f;  // a uniform bias: the agreement test's business, not the σ diagnostic's
    }
    EXPECT_EQ(sigma_diagnostic(z, mask).verdict, SigmaCheck::Plausible);
    EXPECT_EQ(sigma_diagnostic(shifted, mask).verdict, SigmaCheck::Plausible);
    const SigmaDiagnostic over = sigma_diagnostic(half, mask);
    EXPECT_EQ(over.verdict, SigmaCheck::Overestimated);
    EXPECT_NEAR(over.sigma_factor, 0.5, 0.03);
    EXPECT_NE(explain(over).find("2.0× too large"), std::string::npos) << explain(over);
    EXPECT_EQ(sigma_diagnostic(twice, mask).verdict, SigmaCheck::Underestimated);
    EXPECT_NEAR(sigma_diagnostic(z, mask).z_variance_sigma, std::sqrt(2.0 / 1999.0), 1e-12);
    // Five values are no evidence.
    EXPECT_EQ(sigma_diagnostic({0.1f, -0.1f, 0.05f, 0.0f, -0.05f}, std::vector<std::uint8_t>(5, 1))
                  .verdict,
              SigmaCheck::Plausible);
    EXPECT_EQ(to_string(Agreement::ExceedsNoise), "exceeds noise");
    EXPECT_EQ(to_string(SigmaCheck::Underestimated), "σ underestimated");
}
