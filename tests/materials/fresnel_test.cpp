// Fresnel reflection for a complex index: published values and the s/p Mueller convention.

#include "tirpol/materials/fresnel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "tirpol/core/geometry.h"
#include "tirpol/core/stokes.h"

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

// Absorbing media: the time convention exp(i(kr − ωt)) with k ≥ 0 makes q = √(ñ² − sin²θ) lie in
// the first quadrant, and energy conservation gives R ≤ 1 for every k ≥ 0 and angle.
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

// Sense of rotation of the real field of a Jones vector given in the exp(i(k·r − ωt)) convention of
// fresnel_amplitudes, in a right-handed frame (x, y, k): +1 if E(t) = Re(E·e^{−iωt}) turns
// clockwise as seen by a receiver looking into the oncoming light (x to its right, y up), −1 if
// counter-clockwise. Right-handed light is clockwise in the receiver's view (Born & Wolf,
// Principles of Optics, 7th ed., §1.4.2). Computed in the time domain, independently of any Mueller
// algebra.
int receiver_view_rotation(std::complex<double> ex, std::complex<double> ey) {
    const double dt = 1e-3;  // ωt step
    auto field = [&](double wt) {
        const std::complex<double> phase = std::polar(1.0, -wt);
        return Eigen::Vector2d((ex * phase).real(), (ey * phase).real());
    };
    const Eigen::Vector2d e0 = field(0.0), e1 = field(dt);
    const double z = e0.x() * e1.y() - e0.y() * e1.x();  // > 0: counter-clockwise from x toward y
    return z < 0.0 ? 1 : -1;
}

// Jones→Mueller with the time convention converted (fresnel.h): the closed form equals core's
// mueller_from_jones (Chipman et al. 2018 eq 6.99, exp(i(ωt − k·r))) of the conjugated Jones
// matrix.
TEST(Fresnel, MuellerMatchesJonesConversionOfConjugatedAmplitudes) {
    for (const ComplexIndex index :
         {ComplexIndex{1.5, 0.0}, ComplexIndex{1.6, 0.3}, ComplexIndex{12.1, 69.2}})
        for (double deg : {0.0, 30.0, 56.0, 75.0, 89.0}) {
            const double c = std::cos(deg_to_rad(deg));
            const FresnelResult r = fresnel(index, c);
            JonesMatrix j = JonesMatrix::Zero();
            j(0, 0) = std::conj(r.rs);
            j(1, 1) = std::conj(r.rp);
            const MuellerMatrix expected = mueller_from_jones(j);
            const MuellerMatrix m = fresnel_mueller(index, c);
            EXPECT_LT((m - expected).cwiseAbs().maxCoeff(), 1e-12) << index.n << " " << deg;
            EXPECT_TRUE(is_physically_realizable(m));
            EXPECT_GE(m(0, 1), -1e-15);  // reflection favours s: S1 > 0 (pbrdf.h)
        }
}

// Fresnel rhomb (Hecht, Optics, 4th ed., §8.7; Born & Wolf, Principles of Optics, 7th ed., §1.5.4):
// total internal reflection in glass of n = 1.51 at 54.6° retards p against s by 45° (B&W eq 60,
// tan(δ/2) = cosθ·√(sin²θ − n²)/sin²θ with n = 1/1.51: δ = 45.0°), so two reflections turn +45°
// linear light into circular light. Its handedness, from the time-domain field: p is advanced more
// than s
// (|arg r_p| > |arg r_s| with e^{−iωt}), the field goes x → −y, clockwise for the receiver:
// right-circular, S3 = +1 in tirpol's (receiver-view) convention. The two faces' s/p frames differ
// by a 180° rotation, which leaves Stokes vectors unchanged, so the Mueller matrices simply
// multiply.
TEST(Fresnel, RhombTurnsPlus45LinearIntoRightCircular) {
    const ComplexIndex inside{1.0 / 1.51, 0.0};
    const double c = std::cos(deg_to_rad(54.6));
    const FresnelResult r = fresnel(inside, c);
    EXPECT_NEAR(r.Rs, 1.0, 1e-12);  // total internal reflection
    EXPECT_NEAR(r.Rp, 1.0, 1e-12);
    const double retardance_deg = rad_to_deg(std::abs(std::arg(r.rp / r.rs)));
    EXPECT_NEAR(retardance_deg, 45.0, 0.05) << "Born & Wolf eq 60";

    const std::complex<double> ex = r.rs * r.rs,
                               ey = r.rp * r.rp;  // (1, 1)/√2 after two reflections
    EXPECT_EQ(receiver_view_rotation(ex, ey), 1)
        << "the field turns clockwise for the receiver: right-circular";

    const MuellerMatrix m = fresnel_mueller(inside, c);
    const StokesVector out = m * m * linearly_polarized(1.0, 1.0, deg_to_rad(45.0));
    EXPECT_NEAR(out[3], 1.0, 2e-3);  // S3 > 0: right-circular (stokes.h)
    EXPECT_NEAR(std::hypot(out[1], out[2]), 0.0, 3e-3);
}

// A metal is a retarder off normal incidence. Mitsuba 3's comparison case n = 2 + 3i: for +45°
// linear input the sign of S3 from the Mueller matrix must match the rotation sense of the physical
// field at every angle (a convention error once flipped every pixel's S3).
TEST(Fresnel, MetalRetardanceGivesTheS3OfThePhysicalField) {
    for (const ComplexIndex metal : {ComplexIndex{2.0, 3.0}, ComplexIndex{12.1, 69.2}})
        for (double deg : {20.0, 45.0, 60.0, 75.0, 85.0}) {
            const double c = std::cos(deg_to_rad(deg));
            const FresnelResult r = fresnel(metal, c);
            const StokesVector out =
                fresnel_mueller(metal, c) * linearly_polarized(1.0, 1.0, deg_to_rad(45.0));
            ASSERT_GT(std::abs(out[3]), 1e-4) << deg;
            EXPECT_EQ(out[3] > 0.0 ? 1 : -1, receiver_view_rotation(r.rs, r.rp))
                << metal.n << "+" << metal.k << "i at " << deg;
            // In this convention both phases fall with angle and p falls further: δ = arg(r_p/r_s)
            // < 0 between normal (±180°) and grazing (0), so +45° linear light comes back
            // right-handed.
            EXPECT_GT(out[3], 0.0) << deg;
        }
}

}  // namespace
}  // namespace tirpol::materials
