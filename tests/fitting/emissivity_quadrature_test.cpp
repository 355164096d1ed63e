// The fixed-node (Jet-friendly) emissivity quadrature of tirpol::fitting against the materials
// module's own integrator (materials/emissivity.h, sample-space Gauss–Legendre that follows the
// lobe), and against closed forms: a Lambertian surface of albedo πρ_D has ε_S0 = 1 − πρ_D and ε_S1
// = 0 at every angle.

#include <gtest/gtest.h>

#include <cmath>

#include "synthetic_emissivity.h"
#include "tirpol/core/error.h"
#include "tirpol/core/geometry.h"
#include "tirpol/fitting/microfacet_fit.h"
#include "tirpol/materials/emissivity.h"
#include "tirpol/materials/microfacet.h"

namespace tirpol::fitting {
namespace {

materials::EmissivityOptions reference_options() {
    materials::EmissivityOptions o;
    o.radial_panels = 24;
    o.azimuth_panels = 16;
    o.order = 8;
    return o;
}

// Paint-like, rough and smoother-than-paint parameter sets (σ from 0.1 to 0.6, finite τ, Ω, volume
// term).
struct Case {
    const char* what;
    materials::ShellTargetParameters<double> p;
};
const Case kCases[] = {
    {"paint sigma 0.3", {1.6, 0.15, 0.3, 1.0, deg_to_rad(90.0), deg_to_rad(1e6), 0.0, 0.0}},
    {"glossy sigma 0.1", {1.5, 0.05, 0.1, 1.0, deg_to_rad(90.0), deg_to_rad(1e6), 0.0, 0.0}},
    {"rough sigma 0.6 + diffuse + volume, Beard-Maxwell shadowing",
     {2.2, 0.6, 0.6, 0.8, deg_to_rad(20.0), deg_to_rad(50.0), 0.01, 0.005}},
};

TEST(EmissivityQuadrature, AgreesWithMaterialsIntegratorAtEveryAngle) {
    for (const Case& c : kCases) {
        const materials::MicrofacetBrdf brdf = test::brdf_of(c.p);
        for (double angle_deg : {0.0, 15.0, 35.0, 55.0, 70.0, 80.0, 86.0, 89.5}) {
            const double theta = deg_to_rad(angle_deg);
            const StokesVector reference =
                materials::directional_emissivity(brdf, std::cos(theta), 10.0, reference_options());
            const auto [s0, s1] = EmissivityQuadrature(theta).emissivity(c.p);
            SCOPED_TRACE(::testing::Message() << c.what << " at " << angle_deg << " deg");
            EXPECT_NEAR(s0, reference(0), 1e-3);
            EXPECT_NEAR(s1, reference(1), 1e-3);
        }
    }
}

TEST(EmissivityQuadrature, LambertianClosedForm) {
    // bias = 0 leaves only ρ_D: ∫ ρ_D cosθi dωi = π ρ_D; no polarization. The integrand cosθ·sinθ
    // is not a polynomial, so Gauss–Legendre is exact only to the rule's order: 3 nodes per panel
    // give < 1e-5.
    const materials::ShellTargetParameters<double> p{1.5, 0.0, 0.3, 0.0, 1.0, 1.0, 0.05, 0.0};
    for (double angle_deg : {0.0, 45.0, 89.0}) {
        const auto [s0, s1] = EmissivityQuadrature(deg_to_rad(angle_deg), {3}).emissivity(p);
        EXPECT_NEAR(s0, 1.0 - kPi * 0.05, 1e-5);
        EXPECT_NEAR(s1, 0.0, 1e-15);
    }
}

TEST(EmissivityQuadrature, RejectsAnglesOutsideTheHemisphere) {
    EXPECT_THROW(EmissivityQuadrature(-0.1), Error);
    EXPECT_THROW(EmissivityQuadrature(2.0), Error);
    EXPECT_THROW(EmissivityQuadrature(0.5, {0}), Error);
}

}  // namespace
}  // namespace tirpol::fitting
