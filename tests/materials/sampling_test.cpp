// Importance sampling: sampled directions follow the pdf the model reports (χ² goodness of fit, as
// in pbrt-v4's bsdfs_test.cpp), the pdf integrates to the probability of drawing a valid sample,
// and sample weights equal eval·cosθi/pdf.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "lambertian.h"
#include "tirpol/materials/emissivity.h"
#include "tirpol/materials/microfacet.h"

namespace tirpol::materials {
namespace {

std::vector<std::shared_ptr<PolarizedBrdf>> models() {
    MicrofacetParameters rough;
    rough.index = RefractiveIndexTable::constant({1.6, 0.05});
    rough.sigma = 0.3;
    rough.rho_d = 0.01;
    rough.rho_v = 0.02;
    MicrofacetParameters glossy;
    glossy.index = RefractiveIndexTable::constant({12.1, 69.2});
    glossy.sigma = 0.1;
    MicrofacetParameters glossy_paint;  // config/materials/glossy_black_paint.yaml
    glossy_paint.index = RefractiveIndexTable::constant({1.55, 0.1});
    glossy_paint.sigma = 0.05;
    glossy_paint.rho_d = 0.004;
    return {std::make_shared<MicrofacetBrdf>(rough), std::make_shared<MicrofacetBrdf>(glossy),
            std::make_shared<MicrofacetBrdf>(glossy_paint),
            std::make_shared<LambertianBrdf>(SpectralValue(0.4))};
}

constexpr int kThetaBins = 16, kPhiBins = 32;

// ∫ pdf over the bin (cosθ ∈ [c0, c1], φ ∈ [p0, p1]) with a midpoint rule inside the bin: 12 × 12,
// and 100 × 100 in the first and the last two rows of bins, where glossy lobes at normal and
// grazing views (σ = 0.05 at 89°) peak within a fraction of a bin.
double bin_probability(const PolarizedBrdf& brdf, const Vec3& wo, int ti, int pj) {
    const double c0 = 1.0 - static_cast<double>(ti) / kThetaBins, dc = 1.0 / kThetaBins;
    const double p0 = 2.0 * kPi * pj / kPhiBins, dp = 2.0 * kPi / kPhiBins;
    double sum = 0.0;
    const int n = ti == 0 || ti >= kThetaBins - 2 ? 100 : 12;
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
            const double c = c0 - (a + 0.5) * dc / n, p = p0 + (b + 0.5) * dp / n;
            const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
            sum += brdf.pdf({s * std::cos(p), s * std::sin(p), c}, wo, 10.0);
        }
    return sum * dc * dp / (n * n);
}

// Wilson–Hilferty normal approximation of the χ² upper tail (Abramowitz & Stegun 26.4.17).
double chi2_p_value(double chi2, int dof) {
    const double k = dof;
    const double z = (std::cbrt(chi2 / k) - (1.0 - 2.0 / (9.0 * k))) / std::sqrt(2.0 / (9.0 * k));
    return 0.5 * std::erfc(z / std::sqrt(2.0));
}

TEST(Sampling, ChiSquareSampledDirectionsFollowPdf) {
    std::mt19937_64 rng(1234);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (const auto& model : models())
        for (double theta_deg : {10.0, 60.0, 85.0, 89.0}) {
            const double t = deg_to_rad(theta_deg);
            const Vec3 wo(std::sin(t), 0.0, std::cos(t));
            std::vector<double> observed(kThetaBins * kPhiBins, 0.0);
            constexpr int kSamples = 200000;
            for (int s = 0; s < kSamples; ++s) {
                const BrdfSample smp = model->sample(wo, 10.0, u(rng), u(rng));
                if (!(smp.pdf > 0.0)) continue;
                const int ti =
                    std::min(kThetaBins - 1, static_cast<int>((1.0 - smp.wi.z()) * kThetaBins));
                double phi = std::atan2(smp.wi.y(), smp.wi.x());
                if (phi < 0) phi += 2.0 * kPi;
                const int pj =
                    std::min(kPhiBins - 1, static_cast<int>(phi / (2.0 * kPi) * kPhiBins));
                observed[ti * kPhiBins + pj] += 1.0;
            }
            // Pool bins with expected count < 5 (standard χ² practice), then test at p = 1e-4.
            double chi2 = 0.0, pooled_obs = 0.0, pooled_exp = 0.0;
            int dof = -1;
            for (int ti = 0; ti < kThetaBins; ++ti)
                for (int pj = 0; pj < kPhiBins; ++pj) {
                    const double expected = kSamples * bin_probability(*model, wo, ti, pj);
                    const double obs = observed[ti * kPhiBins + pj];
                    if (expected < 5.0) {
                        pooled_obs += obs;
                        pooled_exp += expected;
                        continue;
                    }
                    chi2 += (obs - expected) * (obs - expected) / expected;
                    ++dof;
                }
            if (pooled_exp > 5.0) {
                chi2 += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp;
                ++dof;
            }
            const double p = chi2_p_value(chi2, dof);
            EXPECT_GT(p, 1e-4) << model->model() << " at " << theta_deg << "°: χ² = " << chi2
                               << ", dof " << dof;
        }
}

// ∫ pdf dω over the hemisphere equals the probability that `sample` returns a valid direction (1
// for a Lambertian; less for micro-facets at oblique view, whose reflections can fall below the
// horizon).
TEST(Sampling, PdfIntegratesToProbabilityOfValidSample) {
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (const auto& model : models())
        for (double theta_deg : {0.0, 45.0, 80.0}) {
            const double t = deg_to_rad(theta_deg);
            const Vec3 wo(std::sin(t), 0.0, std::cos(t));
            double integral = 0.0;
            for (int ti = 0; ti < kThetaBins; ++ti)
                for (int pj = 0; pj < kPhiBins; ++pj)
                    integral += bin_probability(*model, wo, ti, pj);
            int valid = 0;
            constexpr int kSamples = 100000;
            for (int s = 0; s < kSamples; ++s)
                valid += model->sample(wo, 10.0, u(rng), u(rng)).pdf > 0.0 ? 1 : 0;
            const double fraction = static_cast<double>(valid) / kSamples;
            EXPECT_NEAR(integral, fraction, 5e-3) << model->model() << " at " << theta_deg;
            if (model->model() == "lambertian") {
                EXPECT_NEAR(integral, 1.0, 2e-3);
            }
        }
}

// The sample's weight is the Monte-Carlo estimator M·cosθi/pdf (pbrdf.h), consistent with eval/pdf.
TEST(Sampling, WeightEqualsEvalTimesCosineOverPdf) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const Vec3 wo = Vec3(0.4, -0.2, 0.8).normalized();
    for (const auto& model : models())
        for (int s = 0; s < 1000; ++s) {
            const BrdfSample smp = model->sample(wo, 10.0, u(rng), u(rng));
            if (!(smp.pdf > 0.0)) continue;
            EXPECT_NEAR(smp.pdf, model->pdf(smp.wi, wo, 10.0), 1e-9 * smp.pdf);
            const MuellerMatrix expected = model->eval(smp.wi, wo, 10.0) * smp.wi.z() / smp.pdf;
            EXPECT_LT((smp.weight - expected).cwiseAbs().maxCoeff(),
                      1e-9 * std::max(1.0, expected(0, 0)));
        }
}

// The visible-normal sampler inverts its CDFs exactly (to 1e-12 in u, so the sampled density is the
// pdf up to rounding): wo along +x, the facet's unit-roughness slopes (x̃, ỹ) = −(h_x, h_y)/(α·h_z)
// satisfy F(x̃) = u1 with F(x̃) = (erfc(−x̃) + tanθ/√π·e^(−x̃²)) / (erfc(−cotθ) + tanθ/√π·e^(−cot²θ)),
// θ the angle of wo stretched by α = √2σ (Heitz & d'Eon 2014, appendix), and Φ(√2·ỹ) =
// erfc(−ỹ)/2 = u2, from u near 0 to near 1 and from near-normal to grazing views (the CDFs here use
// libm's erfc, not the sampler's own quantile function).
TEST(Sampling, VisibleNormalSlopesInvertTheirCdfsExactly) {
    const double inv_sqrt_pi = 1.0 / std::sqrt(kPi);
    const std::vector<double> us = {1e-12, 1e-6, 1e-3, 0.01,  0.1,        0.25,       0.5,
                                    0.75,  0.9,  0.99, 0.999, 1.0 - 1e-6, 1.0 - 1e-10};
    for (double sigma : {0.02, 0.3, 1.0})
        for (double theta_deg : {1.0, 30.0, 60.0, 80.0, 89.0, 89.9}) {
            const double t = deg_to_rad(theta_deg), alpha = std::sqrt(2.0) * sigma;
            const Vec3 wo(std::sin(t), 0.0, std::cos(t));
            const double tan_s = alpha * std::tan(t), cot_s = 1.0 / tan_s;
            const auto cdf_x = [&](double x) {
                return (std::erfc(-x) + tan_s * inv_sqrt_pi * std::exp(-x * x)) /
                       (std::erfc(-cot_s) + tan_s * inv_sqrt_pi * std::exp(-cot_s * cot_s));
            };
            for (double u1 : us)
                for (double u2 : us) {
                    const Vec3 h = sample_visible_normal(wo, sigma, u1, u2);
                    const double x = -h.x() / (alpha * h.z()), y = -h.y() / (alpha * h.z());
                    EXPECT_LE(x, cot_s * (1.0 + 1e-12));
                    EXPECT_NEAR(cdf_x(x), u1, 1e-12)
                        << "σ " << sigma << " at " << theta_deg << "°, u1 " << u1 << ", u2 " << u2;
                    EXPECT_NEAR(0.5 * std::erfc(-y), u2, 1e-12)
                        << "σ " << sigma << " at " << theta_deg << "°, u2 " << u2;
                }
        }
}

// Visible-normal sampling (Heitz & d'Eon, EGSR 2014) bounds the specular weight: with only the
// specular lobe (p_spec = 1, bias 1, no Beard–Maxwell shadowing) the weight is F·G/G1(wo) ≤ 1 for
// every sample, up to grazing views, where D·cosθh sampling gave weights of ~(h·wo)/(cosθo cosθh)
// ≫ 1.
TEST(Sampling, VisibleNormalWeightsAreBoundedUpToGrazing) {
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (double sigma : {0.05, 0.3, 0.6}) {
        MicrofacetParameters metal;
        metal.index = RefractiveIndexTable::constant({12.1, 69.2});
        metal.sigma = sigma;
        const MicrofacetBrdf brdf(metal);
        for (double theta_deg : {0.0, 60.0, 85.0, 89.5}) {
            const double t = deg_to_rad(theta_deg);
            const Vec3 wo(std::sin(t), 0.0, std::cos(t));
            double max_weight = 0.0;
            for (int s = 0; s < 20000; ++s) {
                const BrdfSample smp = brdf.sample(wo, 10.0, u(rng), u(rng));
                if (smp.pdf > 0.0) max_weight = std::max(max_weight, smp.weight(0, 0));
            }
            EXPECT_LE(max_weight, 1.0 + 1e-9) << "σ " << sigma << " at " << theta_deg << "°";
            EXPECT_GT(max_weight, 0.5) << "σ " << sigma << " at " << theta_deg << "°";
        }
    }
}

// The renderer's sampler (visible normals) and the emissivity quadrature's map (slope sampling,
// quadrature_sample) estimate the same integral: the mean weight's first column over 10⁶ samples is
// the directional-hemispherical reflectance e0 − ε of directional_emissivity within 5 standard
// errors
// (+ the quadrature's 2e-4), for rough paint-like and metal models from normal to grazing view.
TEST(Sampling, VisibleNormalEstimatesMatchTheEmissivityQuadrature) {
    std::mt19937_64 rng(23);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (const auto& model : models())
        for (double theta_deg : {5.0, 16.0, 40.0, 70.0, 85.0}) {
            const double t = deg_to_rad(theta_deg);
            const Vec3 wo(std::sin(t), 0.0, std::cos(t));
            constexpr int kSamples = 1000000;
            StokesVector sum = StokesVector::Zero(), sum2 = StokesVector::Zero();
            for (int s = 0; s < kSamples; ++s) {
                const BrdfSample smp = model->sample(wo, 10.0, u(rng), u(rng));
                if (!(smp.pdf > 0.0)) continue;
                const StokesVector w = smp.weight.col(0);
                sum += w;
                sum2 += w.cwiseAbs2();
            }
            const StokesVector mean = sum / kSamples;
            const StokesVector error =
                ((sum2 / kSamples - mean.cwiseAbs2()).cwiseMax(0.0) / kSamples).cwiseSqrt();
            const StokesVector reflected =
                unpolarized(1.0) - directional_emissivity(*model, std::cos(t), 10.0);
            for (int c = 0; c < 2; ++c)
                EXPECT_NEAR(mean(c), reflected(c), 5.0 * error(c) + 2e-4)
                    << model->model() << " S" << c << " at " << theta_deg << "°";
        }
}

}  // namespace
}  // namespace tirpol::materials
