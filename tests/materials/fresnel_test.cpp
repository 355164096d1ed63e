// Fresnel reflection for a complex index: published values and the s/p Mueller convention.

#include <gtest/gtest.h>

#include <cmath>

#include "tirpol/core/geometry.h"
#include "tirpol/core/mueller.h"
#include "tirpol/materials/fresnel.h"

namespace tirpol::materials {
namespace {

// Hecht, Optics (4th ed., 2002) §4.6.2: glass n = 1.5 reflects 4% at normal incidence
// (R = ((n−1)/(n+1))²), and p-light not at all at Brewster's angle θB = atan(n) = 56.31°, where
// s-light reflects Rs = sin²(θi − θt) = 0.1479.
TEST(Fresnel, DielectricNormalIncidenceAndBrewsterAngle) {
    const ComplexIndex glass{1.5, 0.0};
    const FresnelResult normal = fresnel(glass, 1.0);
    EXPECT_NEAR(normal.Rs, 0.04, 1e-12);
    EXPECT_NEAR(normal.Rp, 0.04, 1e-12);
    // Normal incidence in our frames: r_p = −r_s (pbrdf.h/fresnel.h).
    EXPECT_NEAR(normal.rs.real(), -0.2, 1e-12);
    EXPECT_NEAR(normal.rp.real(), 0.2, 1e-12);

    const double brewster = std::atan(1.5);
    const FresnelResult b = fresnel(glass, std::cos(brewster));
    EXPECT_NEAR(b.Rp, 0.0, 1e-15);
    const double theta_t = std::asin(std::sin(brewster) / 1.5);
    EXPECT_NEAR(b.Rs, std::pow(std::sin(brewster - theta_t), 2), 1e-12);
    EXPECT_NEAR(b.Rs, 0.1479, 1e-4);
    // Grazing incidence: every interface is a perfect mirror.
    const FresnelResult g = fresnel(glass, 0.0);
    EXPECT_NEAR(g.Rs, 1.0, 1e-12);
    EXPECT_NEAR(g.Rp, 1.0, 1e-12);
}

// Metals at 10 µm. Gold: n = 12.1, k = 69.2 (Ordal et al., Appl. Opt. 26, 744 (1987), via
// refractiveindex.info); aluminium: n = 26.216, k = 88.197 at 10.332 µm (Rakić, Appl. Opt. 34, 4755
// (1995)). Normal-incidence reflectance ((n−1)² + k²)/((n+1)² + k²) (Born & Wolf §14.2 eq 13):
// 0.9902 for gold and 0.9877 for aluminium, the ≈ 99% LWIR reflectance of these mirror metals that
// Bennett & Ashley (Appl. Opt. 4, 221 (1965)) measured for evaporated films.
TEST(Fresnel, MetalReflectanceAtTenMicrometres) {
    const FresnelResult au = fresnel({12.1, 69.2}, 1.0);
    EXPECT_NEAR(au.R(), 0.9902, 1e-4);
    const FresnelResult al = fresnel({26.216, 88.197}, 1.0);
    EXPECT_NEAR(al.R(), 0.9877, 1e-4);
    // Off normal, a metal reflects s more than p, and Rp has its (pseudo-Brewster) minimum near
    // grazing incidence, above 80° for |ñ| ≈ 70 (Born & Wolf §14.4.1).
    double min_rp = 1.0, min_angle = 0.0;
    for (double deg = 0.5; deg < 90.0; deg += 0.5) {
        const FresnelResult r = fresnel({12.1, 69.2}, std::cos(deg_to_rad(deg)));
        EXPECT_GE(r.Rs, r.Rp - 1e-15) << deg;
        if (r.Rp < min_rp) {
            min_rp = r.Rp;
            min_angle = deg;
        }
    }
    EXPECT_GT(min_angle, 80.0);
    EXPECT_LT(min_rp, 0.99);
}

// Absorbing media: the time convention exp(i(kr − ωt)) with k ≥ 0 makes q = √(ñ² − sin²θ) lie in the
// first quadrant, and energy conservation gives R ≤ 1 for every k ≥ 0 and angle.
TEST(Fresnel, ReflectanceNeverExceedsOne) {
    for (double n : {0.2, 1.0, 1.33, 1.6, 4.0, 30.0})
        for (double k : {0.0, 0.01, 0.5, 5.0, 90.0})
            for (double deg = 0.0; deg <= 90.0; deg += 2.5) {
                const FresnelResult r = fresnel({n, k}, std::cos(deg_to_rad(deg)));
                EXPECT_LE(r.Rs, 1.0 + 1e-12);
                EXPECT_LE(r.Rp, 1.0 + 1e-12);
                EXPECT_GE(r.Rp, 0.0);
            }
}

// The closed-form Mueller matrix equals core's mueller_from_jones(diag(r_s, r_p)) (Chipman et al. 2018
// eq 6.99), which pins the signs of m23/m32 (the retardance block, hence S3) in our frames.
TEST(Fresnel, MuellerMatchesJonesConversion) {
    for (const ComplexIndex index : {ComplexIndex{1.5, 0.0}, ComplexIndex{1.6, 0.3}, ComplexIndex{12.1, 69.2}})
        for (double deg : {0.0, 30.0, 56.0, 75.0, 89.0}) {
            const double c = std::cos(deg_to_rad(deg));
            const FresnelResult r = fresnel(index, c);
            JonesMatrix j = JonesMatrix::Zero();
            j(0, 0) = r.rs;
            j(1, 1) = r.rp;
            const MuellerMatrix expected = mueller_from_jones(j);
            const MuellerMatrix m = fresnel_mueller(index, c);
            EXPECT_LT((m - expected).cwiseAbs().maxCoeff(), 1e-12) << index.n << " " << deg;
            EXPECT_TRUE(is_physically_realizable(m));
            EXPECT_GE(m(0, 1), -1e-15);  // reflection favours s: S1 > 0 (pbrdf.h)
        }
    // A metal off normal incidence is a retarder: the lower block carries a phase, m23 ≠ 0, with
    // m23 = Im(r_s r_p*) > 0 for k > 0 in this convention.
    const MuellerMatrix metal = fresnel_mueller({12.1, 69.2}, std::cos(deg_to_rad(75.0)));
    EXPECT_GT(metal(2, 3), 1e-3);
    EXPECT_NEAR(metal(3, 2), -metal(2, 3), 1e-15);
}

}  // namespace
}  // namespace tirpol::materials
