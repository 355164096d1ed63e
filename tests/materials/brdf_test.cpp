// Physical laws every pBRDF model must obey: Helmholtz reciprocity in Mueller form, physical
// realizability, finiteness at degenerate geometry, polarization of reflection perpendicular to the
// plane of incidence.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "lambertian.h"
#include "smooth_fresnel.h"
#include "tirpol/core/stokes.h"
#include "tirpol/materials/microfacet.h"

namespace tirpol::materials {
namespace {

Vec3 direction(double theta_deg, double phi_deg) {
    const double t = deg_to_rad(theta_deg), p = deg_to_rad(phi_deg);
    return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

std::vector<std::shared_ptr<PolarizedBrdf>> rough_models() {
    std::vector<std::shared_ptr<PolarizedBrdf>> out;
    MicrofacetParameters paint;  // a rough dielectric with diffuse and volume terms
    paint.index = RefractiveIndexTable::constant({1.6, 0.05});
    paint.sigma = 0.3;
    paint.tau_deg = 15.0;
    paint.omega_deg = 60.0;
    paint.rho_d = 0.01;
    paint.rho_v = 0.02;
    out.push_back(std::make_shared<MicrofacetBrdf>(paint));
    MicrofacetParameters metal;  // rough gold, Ordal et al. 1987 at 10 µm
    metal.index = RefractiveIndexTable::constant({12.1, 69.2});
    metal.sigma = 0.08;
    out.push_back(std::make_shared<MicrofacetBrdf>(metal));
    MicrofacetParameters glossy;  // nearly smooth dielectric
    glossy.index = RefractiveIndexTable::constant({1.5, 0.01});
    glossy.sigma = 0.01;
    out.push_back(std::make_shared<MicrofacetBrdf>(glossy));
    out.push_back(std::make_shared<LambertianBrdf>(SpectralValue(0.3)));
    return out;
}

// Helmholtz reciprocity for polarized light (Sekera, JOSA 56, 1732 (1966); Mishchenko, Travis &
// Lacis, "Multiple scattering of light by particles", 2006, eq 13.37): in tirpol's s/p frames
// (pbrdf.h) M(wo→wi) = Q·M(wi→wo)ᵀ·Q with Q = diag(1, 1, −1, 1). Also checked: Q = diag(1,1,1,−1)
// does NOT hold (the test would catch a transposed frame convention).
TEST(Brdf, MuellerReciprocity) {
    const MuellerMatrix q = Eigen::Vector4d(1, 1, -1, 1).asDiagonal();
    const MuellerMatrix wrong_q = Eigen::Vector4d(1, 1, 1, -1).asDiagonal();
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> theta(1.0, 88.0), phi(0.0, 360.0);
    for (const auto& model : rough_models()) {
        double worst_violation = 0.0;
        for (int trial = 0; trial < 200; ++trial) {
            const Vec3 wi = direction(theta(rng), phi(rng)), wo = direction(theta(rng), phi(rng));
            const MuellerMatrix forward = model->eval(wi, wo, 10.0);
            const MuellerMatrix backward = model->eval(wo, wi, 10.0);
            const double scale = std::max(forward(0, 0), 1e-300);
            EXPECT_LT((q * forward.transpose() * q - backward).cwiseAbs().maxCoeff(), 1e-9 * scale)
                << model->model() << " trial " << trial;
            worst_violation = std::max(
                worst_violation,
                (wrong_q * forward.transpose() * wrong_q - backward).cwiseAbs().maxCoeff() / scale);
        }
        if (model->model() == "microfacet") {
            EXPECT_GT(worst_violation, 1e-3);
        }
    }
}

// Every Mueller BRDF must be a non-negative sum of non-depolarizing elements: its Cloude coherency
// matrix is positive semi-definite (Cloude 1986; core's is_physically_realizable).
TEST(Brdf, EveryMuellerBrdfIsPhysicallyRealizable) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> theta(0.0, 89.9), phi(0.0, 360.0);
    for (const auto& model : rough_models())
        for (int trial = 0; trial < 500; ++trial) {
            const MuellerMatrix m =
                model->eval(direction(theta(rng), phi(rng)), direction(theta(rng), phi(rng)), 10.0);
            ASSERT_TRUE(is_physically_realizable(m, 1e-9)) << model->model() << "\n" << m;
        }
}

// Degenerate geometry must not produce NaN/Inf (ARCHITECTURE.md "no artifacts at grazing angles"):
// normal incidence and view, collinear (backscatter) directions, mirror directions, exactly
// grazing.
TEST(Brdf, FiniteAtNormalCollinearAndGrazingGeometry) {
    const std::vector<std::pair<Vec3, Vec3>> cases = {
        {Vec3::UnitZ(), Vec3::UnitZ()},                        // normal, collinear
        {direction(40, 30), direction(40, 30)},                // backscatter
        {direction(40, 30), direction(40, 210)},               // mirror
        {direction(89.999999, 0), direction(89.999999, 180)},  // grazing mirror
        {direction(89.999999, 0), direction(89.999999, 0)},    // grazing backscatter
        {Vec3(1, 0, 1e-300).normalized(), direction(30, 90)},  // at the horizon
        {Vec3(1, 0, 0), direction(30, 90)},                    // exactly in the plane
        {Vec3::UnitZ(), direction(89.9999, 45)},
    };
    for (const auto& model : rough_models())
        for (const auto& [wi, wo] : cases) {
            const MuellerMatrix m = model->eval(wi, wo, 10.0);
            EXPECT_TRUE(m.allFinite())
                << model->model() << " wi " << wi.transpose() << " wo " << wo.transpose();
            EXPECT_GE(m(0, 0), 0.0);
            const double p = model->pdf(wi, wo, 10.0);
            EXPECT_TRUE(std::isfinite(p) && p >= 0.0);
            for (double u : {0.0, 0.5, 0.999999})
                EXPECT_TRUE(model->sample(wo, 10.0, u, u).weight.allFinite());
        }
}

// Reflection is polarized perpendicular to the plane of incidence (s, S1 > 0) for a dielectric: for
// unpolarized light the reflected Stokes vector is M·e0, whose S1 = m10 > 0 in the specular
// direction (Fresnel: Rs ≥ Rp; Born & Wolf §1.5.3).
TEST(Brdf, SpecularReflectionIsSPolarized) {
    const auto models = rough_models();
    for (double theta : {20.0, 45.0, 60.0, 80.0}) {
        const MuellerMatrix m = models[0]->eval(direction(theta, 0), direction(theta, 180), 10.0);
        EXPECT_GT(m(1, 0), 0.0) << theta;
        EXPECT_LE(std::abs(m(1, 0)), m(0, 0));
    }
}

}  // namespace
}  // namespace tirpol::materials
