// The micro-facet formulas of shell_target_math.h checked against independent constructions.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tirpol/core/stokes.h"
#include "tirpol/materials/fresnel.h"
#include "tirpol/materials/microfacet.h"

namespace tirpol::materials {
namespace {

Vec3 direction(double theta, double phi) {
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

// smith_lambda in double takes erfc from Cody's rational functions on its own e^(−a²)
// (smith_lambda_from_gaussian); it must agree with the file comment's formula evaluated with libm's
// erfc and exp, to rounding in 1 + Λ, the only form in which Λ enters G, from grazing (a = 1e-4,
// Λ ≈ 2800) to normal views (Λ below 1e-17), for glossy to very rough surfaces.
TEST(ShellTargetMath, SmithLambdaInDoubleAgreesWithTheLibmFormula) {
    for (double sigma : {0.02, 0.1, 0.35, 1.0})
        for (double a = 1e-4; a < 40.0; a *= 1.07) {
            const double cot = a * std::sqrt(2.0) * sigma;
            const double reference = 0.5 * (std::exp(-a * a) / (a * std::sqrt(kPi)) - std::erfc(a));
            EXPECT_NEAR(smith_lambda(sigma, cot), reference, 1e-15 * (1.0 + reference))
                << "σ " << sigma << ", a " << a;
        }
}

// Smith's masking function with the Gaussian facet density satisfies the projected-area identity
// ∫ G1(wo, h) D(h) max(0, h·wo) dωh = cos θo (Heitz, JCGT 3(2), 2014, eq 17), with
// G1 = 1/(1 + Λ(θo)). This pins the normalisation of D and the form of Λ together.
TEST(ShellTargetMath, SmithMaskingConservesProjectedArea) {
    for (double sigma : {0.1, 0.3, 0.6})
        for (double theta_o_deg : {0.0, 45.0, 75.0, 88.0}) {
            const double t = deg_to_rad(theta_o_deg);
            const Vec3 wo = direction(t, 0.0);
            const double cot = theta_o_deg == 0.0 ? 1e8 : std::cos(t) / std::sin(t);
            const double g1 = 1.0 / (1.0 + smith_lambda(sigma, cot));
            // Integrate over facet normals in slope space (tan θh up to 12σ), midpoint rule.
            constexpr int n_r = 1500, n_p = 360;
            const double t_max = 12.0 * sigma;
            double sum = 0.0;
            for (int i = 0; i < n_r; ++i) {
                const double tan_h = (i + 0.5) * t_max / n_r;
                const double cos_h = 1.0 / std::sqrt(1.0 + tan_h * tan_h);
                const double theta_h = std::atan(tan_h);
                const double d = gaussian_facet_density(sigma, cos_h, tan_h * tan_h);
                // dω = sinθ dθ dφ, dθ = cos²θ d(tanθ).
                const double dw =
                    std::sin(theta_h) * cos_h * cos_h * (t_max / n_r) * (2.0 * kPi / n_p);
                for (int j = 0; j < n_p; ++j) {
                    const Vec3 h = direction(theta_h, (j + 0.5) * 2.0 * kPi / n_p);
                    sum += d * std::max(0.0, h.dot(wo)) * dw;
                }
            }
            EXPECT_NEAR(g1 * sum, std::cos(t), 2e-3 * std::max(std::cos(t), 0.05))
                << "sigma " << sigma << " theta " << theta_o_deg;
        }
}

// The frame rotations of microfacet_geometry equal core's change_frame from the facet's s/p frames
// to the macro-surface s/p frames (paper eqs 11–12; Priest & Germer 2000's construction).
TEST(ShellTargetMath, FacetFrameRotationsMatchCoreChangeFrame) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> theta(0.01, 1.5), phi(0.0, 2.0 * kPi);
    const ShellTargetParameters<double> p{1.6, 0.3, 0.3, 1.0, deg_to_rad(20.0), deg_to_rad(50.0),
                                          0.0, 0.0};
    for (int trial = 0; trial < 100; ++trial) {
        const Vec3 wi = direction(theta(rng), phi(rng)), wo = direction(theta(rng), phi(rng));
        const MicrofacetGeometry g = microfacet_geometry(wi, wo);
        const Mueller4<double> m = shell_target_mueller(p, g);
        const Vec3 h = (wi + wo).normalized(), n = Vec3::UnitZ();
        MuellerMatrix expected =
            change_frame(fresnel_mueller({p.n, p.k}, h.dot(wi)), surface_frame(-wi, h),
                         surface_frame(-wi, n), surface_frame(wo, h), surface_frame(wo, n));
        const double scale = m[0][0] / expected(0, 0);
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c)
                EXPECT_NEAR(m[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)],
                            scale * expected(r, c), 1e-12 * m[0][0]);
    }
}

// Beard–Maxwell's SO is 1 at θN = 0 (no tilt, no shadowing) and tends to exp(−2β/τ) for θN ≫ Ω
// (Maxwell et al. 1973, as implemented in SCATMECH's Maxwell_Beard_Shadow_Function).
TEST(ShellTargetMath, BeardMaxwellLimits) {
    EXPECT_DOUBLE_EQ(beard_maxwell_shadowing(0.3, 0.5, 0.0, 0.7), 1.0);
    EXPECT_NEAR(beard_maxwell_shadowing(0.3, 1e-6, 1.0, 0.7), std::exp(-2.0 * 0.7 / 0.3), 1e-6);
}

}  // namespace
}  // namespace tirpol::materials
