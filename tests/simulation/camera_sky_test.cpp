// Camera geometry and the sky model.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "tirpol/core/config.h"
#include "tirpol/core/error.h"
#include "tirpol/simulation/pinhole_camera.h"
#include "tirpol/simulation/scene.h"

namespace tirpol::simulation {
namespace {

TEST(PinholeCamera, ImageFrameIsCameraRightAndUp) {
    const PinholeCamera cam = PinholeCamera::from_config(ConfigNode::parse(
        "{resolution: [64, 48], fov_deg: 40, position: [0, -5, 1], look_at: [0, 0, 1]}"));
    const Vec3 d = cam.ray_direction(32.0, 24.0);
    EXPECT_NEAR((d - Vec3(0, 1, 0)).norm(), 0.0, 1e-12) << "principal ray looks at the target";
    const StokesFrame f = cam.image_frame(d);
    EXPECT_NEAR((f.reference - Vec3(1, 0, 0)).norm(), 0.0, 1e-12)
        << "0° along image +x (east here)";
    EXPECT_NEAR((f.second_axis() - Vec3(0, 0, 1)).norm(), 0.0, 1e-12)
        << "90° toward the image top (up)";
    // A pixel to the right of the centre looks to the right; a pixel above looks up.
    EXPECT_GT(cam.ray_direction(60.0, 24.0).x(), 0.0);
    EXPECT_GT(cam.ray_direction(32.0, 2.0).z(), 0.0);
    // 40° horizontal field of view: the left/right image edges are ±20° off axis.
    EXPECT_NEAR(rad_to_deg(std::acos(cam.ray_direction(64.0, 24.0).dot(d))), 20.0, 1e-9);
}

// Mitsuba 3's stokes integrator takes x = ray.d × camera-up per ray, tirpol camera-right projected
// onto the wavefront. For a ray with direction cosines (a, b, c) on camera right, up and forward
// both axes lie in the wavefront, x_t ∝ R − a·d and x_m ∝ c·R − a·F, so they make the angle φ with
// cos φ = c / √((1 − a²)(1 − b²)): zero on the centre row and column, of opposite signs in
// neighbouring quadrants, 5.17° at the corners of a 40° 4:3 view (docs/simulation.md).
// bench/simulation_bench.cpp rotates Mitsuba's Stokes images by it pixel by pixel.
TEST(PinholeCamera, ImageFrameDiffersFromMitsubasOffAxisOnly) {
    const PinholeCamera cam = PinholeCamera::from_config(ConfigNode::parse(
        "{resolution: [320, 240], fov_deg: 40, position: [0, -5, 1.5], look_at: [0, 0, 0.6]}"));
    const Mat3& axes = cam.world_from_camera();  // columns: right, down, forward
    const Vec3 right = axes.col(0), up = -axes.col(1), forward = axes.col(2);
    const auto angle = [&](double u, double v) {
        const Vec3 d = cam.ray_direction(u, v);
        return frame_rotation_angle(StokesFrame{-d, d.cross(up).normalized()}, cam.image_frame(d));
    };
    for (const auto& [u, v] :
         {std::pair{160.0, 120.0}, {160.0, 0.0}, {0.0, 120.0}, {0.0, 0.0}, {250.0, 30.0}}) {
        const Vec3 d = cam.ray_direction(u, v);
        const double a = d.dot(right), b = d.dot(up), c = d.dot(forward);
        const double expected = std::acos(std::min(1.0, c / std::sqrt((1 - a * a) * (1 - b * b))));
        EXPECT_NEAR(std::abs(angle(u, v)), expected, 1e-6) << u << ", " << v;
        EXPECT_NEAR(angle(u, v), -angle(320.0 - u, v), 1e-9)
            << "mirror image across the centre column";
    }
    EXPECT_NEAR(angle(160.0, 0.0), 0.0, 1e-6);
    EXPECT_NEAR(angle(0.0, 120.0), 0.0, 1e-6);
    EXPECT_NEAR(rad_to_deg(std::abs(angle(0.0, 0.0))), 5.17, 0.005);
}

TEST(PinholeCamera, DistortionIsInvertedExactly) {
    // Forward Brown–Conrady model as in OpenCV's projectPoints; ray_direction must invert it.
    const CameraIntrinsics k{500.0, 505.0, 320.0, 256.0, -0.25, 0.08, 0.001, -0.0015, -0.01};
    const PinholeCamera cam(640, 512, k, Vec3::Zero(), Mat3::Identity());
    for (const auto& [x, y] : {std::pair{0.3, -0.2}, std::pair{-0.5, 0.4}, std::pair{0.05, 0.02}}) {
        const double r2 = x * x + y * y, radial = 1 + r2 * (k.k1 + r2 * (k.k2 + r2 * k.k3));
        const double xd = x * radial + 2 * k.p1 * x * y + k.p2 * (r2 + 2 * x * x);
        const double yd = y * radial + k.p1 * (r2 + 2 * y * y) + 2 * k.p2 * x * y;
        const Vec3 d = cam.ray_direction(k.fx * xd + k.cx, k.fy * yd + k.cy);
        EXPECT_NEAR(d.x() / d.z(), x, 1e-9);
        EXPECT_NEAR(d.y() / d.z(), y, 1e-9);
    }
}

TEST(PinholeCamera, ConfigErrorsNameTheField) {
    try {
        PinholeCamera::from_config(ConfigNode::parse(
            "{resolution: [64, 48], fov_deg: 40, position: [0, 0], look_at: [0, 1, 0]}",
            "cam.yaml"));
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("position"), std::string::npos) << e.what();
    }
}

TEST(Sky, ClearSkyFollowsBerdahlMartinAngularForm) {
    // ε(θ) = 1 − (1 − ε_z)^(1/cos θ) (Berdahl & Martin 1984): ε(0) = ε_z, ε(60°) = 1 − (1 − ε_z)²,
    // ε → 1 at the horizon.
    const Sky sky = Sky::clear_sky(280.0, 0.7);
    EXPECT_NEAR(sky.emissivity(1.0), 0.7, 1e-12);
    EXPECT_NEAR(sky.emissivity(0.5), 1.0 - 0.09, 1e-12);
    EXPECT_NEAR(sky.emissivity(0.0), 1.0, 1e-12);
    EXPECT_NEAR(sky.spectral_radiance(10.0, Vec3(0, 0, 1)), 0.7 * planck_radiance(10.0, 280.0),
                1e-12);
    double previous = 0.0;
    for (double c = 1.0; c >= 0.0; c -= 0.01) {
        EXPECT_GE(sky.emissivity(c), previous);
        previous = sky.emissivity(c);
    }
}

TEST(Sky, TableReproducesItsBandRadiances) {
    const Band band(8.0, 14.0);
    const Sky sky =
        Sky::table({0.0, 45.0, 90.0},
                   {band.radiance(230.0), band.radiance(250.0), band.radiance(280.0)}, band);
    EXPECT_NEAR(sky.temperature_k(1.0), 230.0, 1e-5);
    EXPECT_NEAR(sky.temperature_k(std::cos(deg_to_rad(22.5))), 240.0, 1e-5);
    EXPECT_NEAR(sky.temperature_k(-0.3), 280.0, 1e-5) << "below the horizon: horizon value";
    EXPECT_THROW(Sky::table({0.0, 0.0}, {1.0, 2.0}, band), Error);
}

TEST(Sky, SunFromElevationAndAzimuth) {
    const Band band(3.0, 5.0);
    const Sun sun =
        Sun::from_config(ConfigNode::parse("{elevation_deg: 18, azimuth_deg: 90}"), band);
    EXPECT_NEAR(sun.direction.x(), std::cos(deg_to_rad(18.0)), 1e-12) << "azimuth 90° is east (+x)";
    EXPECT_NEAR(sun.direction.z(), std::sin(deg_to_rad(18.0)), 1e-12);
}

}  // namespace
}  // namespace tirpol::simulation
