// Stokes reference frames and their rotation (paper §2.3.3, eqs 7–11), pinned to ARCHITECTURE.md.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tirpol/core/stokes.h"

namespace tirpol {
namespace {

Vec3 random_unit(std::mt19937& rng) {
    std::normal_distribution<double> n;
    return Vec3(n(rng), n(rng), n(rng)).normalized();
}

TEST(StokesFrame, WorldFrameOfAnUprightViewIsTheImageFrame) {
    // Camera looking north, level: light travels south. Image +x (0°) is east, 90° is up.
    const StokesFrame f = world_frame(Vec3(0, -1, 0));
    EXPECT_TRUE(f.reference.isApprox(Vec3(1, 0, 0), 1e-15));
    EXPECT_TRUE(f.second_axis().isApprox(Vec3(0, 0, 1), 1e-15));
}

TEST(StokesFrame, SPolarizedLightOnAnUntiltedFacetStaysS1PlusOne) {
    // For a horizontal facet the world frame (reference horizontal) is the facet's s/p frame:
    // horizontally (s-) polarized light keeps S1 = +1 in the surface frame.
    std::mt19937 rng(3);
    for (int i = 0; i < 100; ++i) {
        const Vec3 k = random_unit(rng);
        if (std::abs(k.z()) > 0.999) continue;
        const StokesVector s =
            change_frame(StokesVector(1, 1, 0, 0), world_frame(k), surface_frame(k, Vec3::UnitZ()));
        EXPECT_NEAR(s[1], 1.0, 1e-12);
        EXPECT_NEAR(s[2], 0.0, 1e-12);
    }
}

TEST(StokesFrame, RotationThenInverseIsIdentity) {
    std::mt19937 rng(5);
    for (int i = 0; i < 100; ++i) {
        const Vec3 k = random_unit(rng), n = random_unit(rng);
        const StokesFrame a = world_frame(k), b = surface_frame(k, n);
        const StokesVector s(1.0, 0.3, -0.2, 0.1);
        EXPECT_TRUE(change_frame(change_frame(s, a, b), b, a).isApprox(s, 1e-12));
        EXPECT_NEAR(frame_rotation_angle(a, b), -frame_rotation_angle(b, a), 1e-12);
    }
}

TEST(StokesFrame, AgreesWithThePapersEquations7To10) {
    std::mt19937 rng(11);
    for (int i = 0; i < 200; ++i) {
        const Vec3 v = random_unit(rng), n = random_unit(rng);
        const double ours = frame_rotation_angle(world_frame(v), surface_frame(v, n));
        const double paper = paper_rotation_angle(v, n);
        // Stokes rotation depends on 2α, so angles agree modulo π.
        EXPECT_NEAR(std::cos(2 * ours), std::cos(2 * paper), 1e-9);
        EXPECT_NEAR(std::sin(2 * ours), std::sin(2 * paper), 1e-9);
    }
}

TEST(StokesFrame, TiltedSurfaceRotatesByItsTiltAngle) {
    // The paper's example: a surface tilted 45° about an axis in the plane of the incident light
    // (here: light travelling north, surface tilted about the north axis) sees vertical light at
    // 45°.
    const Vec3 k(0, 1, 0);
    const Vec3 n = Vec3(std::sin(kPi / 4), 0, std::cos(kPi / 4));
    EXPECT_NEAR(std::abs(frame_rotation_angle(world_frame(k), surface_frame(k, n))), kPi / 4,
                1e-12);
}

TEST(StokesFrame, DegenerateGeometryStaysFinite) {
    // View straight down (k parallel to up) and normal incidence (k parallel to n): atan2, no 0/0.
    for (const Vec3& k : {Vec3(0, 0, -1), Vec3(0, 0, 1), Vec3(1e-17, 0, -1)}) {
        const StokesFrame w = world_frame(k), s = surface_frame(k, Vec3(0, 0, 1));
        EXPECT_TRUE(w.reference.allFinite());
        EXPECT_NEAR(w.reference.norm(), 1.0, 1e-12);
        EXPECT_NEAR(w.reference.dot(w.propagation), 0.0, 1e-12);
        EXPECT_TRUE(std::isfinite(frame_rotation_angle(w, s)));
        EXPECT_TRUE(std::isfinite(paper_rotation_angle(k, Vec3(0, 0, 1))));
    }
}

TEST(StokesFrame, RotatingTheSceneAboutTheVerticalLeavesCameraStokesUnchanged) {
    // Light leaving a tilted facet towards the camera, expressed in the camera (world) frame, must
    // not depend on the azimuth of the whole scene.
    const Vec3 k0 = Vec3(0.3, -0.9, 0.2).normalized(), n0 = Vec3(0.2, -0.4, 0.9).normalized();
    const StokesVector in_surface(1.0, -0.2, 0.05, 0.0);
    const StokesVector ref = change_frame(in_surface, surface_frame(k0, n0), world_frame(k0));
    for (double az : {0.3, 1.7, 3.1, 4.4}) {
        const Eigen::AngleAxisd r(az, Vec3::UnitZ());
        const Vec3 k = r * k0, n = r * n0;
        const StokesVector s = change_frame(in_surface, surface_frame(k, n), world_frame(k));
        EXPECT_TRUE(s.isApprox(ref, 1e-12)) << az;
    }
}

}  // namespace
}  // namespace tirpol
