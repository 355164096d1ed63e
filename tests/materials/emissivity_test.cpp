// Kirchhoff-consistent polarized emissivity (paper eq 5 as Stokes): exact cases, agreement with a
// brute-force hemispherical integration, the σ → 0 limit, and the table.

#include <gtest/gtest.h>

#include <cmath>

#include "tirpol/core/stokes.h"
#include "tirpol/materials/emissivity.h"
#include "tirpol/materials/fresnel.h"
#include "tirpol/materials/lambertian.h"
#include "tirpol/materials/microfacet.h"
#include "tirpol/materials/smooth_fresnel.h"

namespace tirpol::materials {
namespace {

MicrofacetBrdf paint(double sigma) {
    MicrofacetParameters p;
    p.index = RefractiveIndexTable::constant({1.6, 0.05});
    p.sigma = sigma;
    p.tau_deg = 15.0;
    p.omega_deg = 60.0;
    p.rho_d = 0.01;
    p.rho_v = 0.02;
    return MicrofacetBrdf(p);
}

// Brute force: ∫ M(wi→wo) e0 cosθi dωi on a fine product grid in (θi, φi), independent of the
// models' sampling; midpoint rule, `n_theta` × `n_phi` cells.
StokesVector brute_force_reflected(const PolarizedBrdf& brdf, double theta_o, int n_theta, int n_phi) {
    const Vec3 wo(std::sin(theta_o), 0.0, std::cos(theta_o));
    StokesVector sum = StokesVector::Zero();
    const double dt = 0.5 * kPi / n_theta, dp = 2.0 * kPi / n_phi;
    for (int i = 0; i < n_theta; ++i) {
        const double t = (i + 0.5) * dt;
        for (int j = 0; j < n_phi; ++j) {
            const double p = (j + 0.5) * dp;
            const Vec3 wi(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
            sum += brdf.eval(wi, wo, 10.0).col(0) * (std::cos(t) * std::sin(t) * dt * dp);
        }
    }
    return sum;
}

// A smooth interface emits ε = (1 − R, −(Rs − Rp)/2, 0, 0) (Kirchhoff + Fresnel; Sandus, Appl. Opt.
// 4, 1634 (1965)): the delta lobe is integrated exactly.
TEST(Emissivity, SmoothSurfaceIsOneMinusFresnel) {
    const SmoothFresnelBrdf glass(RefractiveIndexTable::constant({1.5, 0.0}));
    for (double deg : {0.0, 30.0, 56.31, 80.0, 89.9}) {
        const double c = std::cos(deg_to_rad(deg));
        const FresnelResult r = fresnel({1.5, 0.0}, c);
        const StokesVector e = directional_emissivity(glass, c, 10.0);
        EXPECT_NEAR(e(0), 1.0 - r.R(), 1e-12);
        EXPECT_NEAR(e(1), -0.5 * (r.Rs - r.Rp), 1e-12);
        EXPECT_NEAR(e(2), 0.0, 1e-12);
        EXPECT_NEAR(e(3), 0.0, 1e-12);
    }
}

// A Lambertian surface of reflectance ρ has ε = 1 − ρ, unpolarized, at every angle (Kirchhoff's law).
TEST(Emissivity, LambertianIsOneMinusReflectance) {
    const LambertianBrdf lambert(SpectralValue(0.3));
    for (double deg : {0.0, 45.0, 89.9}) {
        const StokesVector e = directional_emissivity(lambert, std::cos(deg_to_rad(deg)), 10.0);
        EXPECT_NEAR(e(0), 0.7, 1e-12);
        EXPECT_NEAR(e.tail<3>().norm(), 0.0, 1e-12);
    }
}

// The sample-space quadrature agrees with a brute-force 2-D integration over the hemisphere
// (1000 × 2000 cells), to the tolerance stated in emissivity.h.
TEST(Emissivity, QuadratureMatchesBruteForceIntegration) {
    for (double sigma : {0.3, 0.15}) {
        const MicrofacetBrdf brdf = paint(sigma);
        for (double deg : {0.0, 40.0, 70.0, 85.0}) {
            const double t = deg_to_rad(deg);
            const StokesVector fast = hemispherical_reflected_stokes(brdf, std::cos(t), 10.0);
            const StokesVector slow = brute_force_reflected(brdf, t, 1000, 2000);
            EXPECT_LT((fast - slow).cwiseAbs().maxCoeff(), 2e-4) << "sigma " << sigma << " at " << deg << "°\n"
                                                                 << fast.transpose() << "\n" << slow.transpose();
        }
    }
}

}  // namespace
}  // namespace tirpol::materials
