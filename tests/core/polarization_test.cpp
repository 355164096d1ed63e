// Stokes vectors and Mueller matrices of standard elements (Collett 2005; Chipman, Lam & Young
// 2018).

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>

#include "tirpol/core/error.h"
#include "tirpol/core/geometry.h"
#include "tirpol/core/stokes.h"

namespace tirpol {
namespace {

TEST(Stokes, DolpAndAopOfLinearLight) {
    const StokesVector s = linearly_polarized(2.0, 0.25, deg_to_rad(30.0));
    EXPECT_NEAR(dolp(s), 0.25, 1e-12);
    EXPECT_NEAR(rad_to_deg(aop_rad(s)), 30.0, 1e-10);
    EXPECT_NEAR(aop_deg_0_180(linearly_polarized(1.0, 1.0, deg_to_rad(-30.0))), 150.0, 1e-10);
    EXPECT_EQ(dolp(unpolarized(0.0)), 0.0);
}

TEST(Stokes, Realizability) {
    EXPECT_TRUE(is_realizable({1, 1, 0, 0}));
    EXPECT_TRUE(is_realizable({1, 0.6, 0.8, 0}));
    EXPECT_FALSE(is_realizable({1, 0.8, 0.8, 0}));
    EXPECT_FALSE(is_realizable({-1, 0, 0, 0}));
    EXPECT_FALSE(is_realizable({1, std::nan(""), 0, 0}));
}

TEST(Mueller, LinearPolarizerFollowsMalusLaw) {
    // Malus's law: I = I0·cos²(θ − φ) for fully polarized light at φ through a polarizer at θ.
    for (double phi : {0.0, 20.0, 45.0, 90.0, 133.0})
        for (double theta : {0.0, 45.0, 90.0, 135.0}) {
            const StokesVector out =
                linear_polarizer(deg_to_rad(theta)) * linearly_polarized(1.0, 1.0, deg_to_rad(phi));
            const double c = std::cos(deg_to_rad(theta - phi));
            EXPECT_NEAR(out[0], c * c, 1e-12) << theta << " " << phi;
            EXPECT_NEAR(dolp(out), out[0] > 1e-12 ? 1.0 : 0.0, 1e-9);
        }
}

TEST(Mueller, PolarizersAtZeroNinetyAndPlusMinus45GiveExpectedStokes) {
    const StokesVector u = unpolarized(1.0);
    const StokesVector h = linear_polarizer(0.0) * u, v = linear_polarizer(kPi / 2) * u;
    const StokesVector p = linear_polarizer(kPi / 4) * u, m = linear_polarizer(-kPi / 4) * u;
    EXPECT_TRUE(h.isApprox(StokesVector(0.5, 0.5, 0, 0), 1e-12));
    EXPECT_TRUE(v.isApprox(StokesVector(0.5, -0.5, 0, 0), 1e-12));
    EXPECT_TRUE(p.isApprox(StokesVector(0.5, 0, 0.5, 0), 1e-12));
    EXPECT_TRUE(m.isApprox(StokesVector(0.5, 0, -0.5, 0), 1e-12));
    // Crossed polarizers extinguish.
    EXPECT_NEAR((linear_polarizer(kPi / 2) * h)[0], 0.0, 1e-15);
}

TEST(Mueller, NonIdealPolarizerLeaksOneOverExtinctionRatio) {
    // The paper's wire grid: extinction ratio > 400:1 (§3.1).
    const MuellerMatrix m = polarizer_with_extinction(0.0, 0.7, 400.0);
    const double along = (m * linearly_polarized(1, 1, 0))[0],
                 across = (m * linearly_polarized(1, 1, kPi / 2))[0];
    EXPECT_NEAR(along, 0.7, 1e-12);
    EXPECT_NEAR(along / across, 400.0, 1e-9);
    EXPECT_THROW(polarizer_with_extinction(0.0, 0.7, 0.5), Error);
}

TEST(Mueller, QuarterWavePlateAt45TurnsHorizontalIntoRightCircular) {
    // Collett, Field Guide to Polarization (SPIE 2005), quarter-wave retarder at +45°: rows
    // (1,0,0,0), (0,0,0,−1), (0,0,1,0), (0,1,0,0), so horizontal light leaves with S3 = +1. In
    // tirpol's receiver-view convention that is right-circular: the field turns from the fast axis
    // (+45°) toward the slow one (−45°), clockwise for an observer looking at the source (Hecht
    // §8.2).
    const StokesVector out = linear_retarder(kPi / 4, kPi / 2) * linearly_polarized(1, 1, 0);
    EXPECT_NEAR(out[3], 1.0, 1e-12);
    EXPECT_NEAR(out[1], 0.0, 1e-12);
    EXPECT_NEAR(out[2], 0.0, 1e-12);
}

TEST(Mueller, FrameRotationThereAndBackIsIdentity) {
    for (double a : {0.1, 0.7, 2.0, -1.3})
        EXPECT_TRUE(
            (frame_rotation(a) * frame_rotation(-a)).isApprox(MuellerMatrix::Identity(), 1e-14));
    // Eq 11: light polarized along the new reference axis has S1 = S0 in the rotated frame.
    const StokesVector s =
        frame_rotation(deg_to_rad(30.0)) * linearly_polarized(1, 1, deg_to_rad(30.0));
    EXPECT_NEAR(s[1], 1.0, 1e-12);
    EXPECT_NEAR(s[2], 0.0, 1e-12);
}

TEST(Mueller, JonesPolarizerMatchesMueller) {
    JonesMatrix j;
    j << 1, 0, 0, 0;
    EXPECT_TRUE(mueller_from_jones(j).isApprox(linear_polarizer(0.0), 1e-14));
    // Quarter-wave plate, fast axis horizontal, Jones vectors in the exp(i(ωt − kz)) convention:
    // the slow (y) field lags, diag(1, −i) up to a global phase.
    JonesMatrix qwp;
    qwp << 1, 0, 0, std::complex<double>(0, -1);
    EXPECT_TRUE(mueller_from_jones(qwp).isApprox(linear_retarder(0.0, kPi / 2), 1e-14));
}

TEST(Mueller, StandardElementsAreRealizableAndCloudeHasRankOneForPureElements) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> angle(0.0, kPi), unit(0.0, 1.0);
    for (int i = 0; i < 50; ++i) {
        const MuellerMatrix elements[] = {
            linear_polarizer(angle(rng)),
            linear_diattenuator(angle(rng), unit(rng), unit(rng) * 0.5),
            linear_retarder(angle(rng), 2 * angle(rng)), frame_rotation(angle(rng))};
        MuellerMatrix product = MuellerMatrix::Identity();
        for (const auto& m : elements) {
            EXPECT_TRUE(is_physically_realizable(m));
            product = m * product;
            // A pure (non-depolarizing) element has a rank-1 coherency matrix (Cloude 1986).
            Eigen::SelfAdjointEigenSolver<Eigen::Matrix4cd> es(cloude_coherency(m));
            const auto ev = es.eigenvalues();
            EXPECT_NEAR(ev[0], 0.0, 1e-12);
            EXPECT_NEAR(ev[2], 0.0, 1e-12);
            EXPECT_NEAR(ev[3], m(0, 0), 1e-12);
        }
        EXPECT_TRUE(is_physically_realizable(product));
        EXPECT_TRUE(is_physically_realizable(depolarizer(unit(rng))));
    }
}

TEST(Mueller, UnphysicalMatricesAreRejected) {
    MuellerMatrix gain = MuellerMatrix::Identity();
    gain(1, 1) = 2.0;  // would polarize beyond 100 %
    EXPECT_FALSE(is_physically_realizable(gain));
    MuellerMatrix negative = MuellerMatrix::Identity();
    negative(0, 1) = 1.5;  // negative intensity for (1, −1, 0, 0)
    EXPECT_FALSE(is_physically_realizable(negative));
    EXPECT_FALSE(is_physically_realizable(-MuellerMatrix::Identity()));
    MuellerMatrix nan = MuellerMatrix::Identity();
    nan(2, 2) = std::nan("");
    EXPECT_FALSE(is_physically_realizable(nan));
}

}  // namespace
}  // namespace tirpol
