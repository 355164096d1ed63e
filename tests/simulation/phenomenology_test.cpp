// Phenomenology the paper reports (§4; ARCHITECTURE.md "Stokes reference"):
//  - a warm smooth ball under a cold sky emits radially polarized light: S1 < 0 at 12 and 6
//  o'clock,
//    S1 > 0 at 3 and 9, S2 > 0 at 1:30 and 7:30, S2 < 0 at 10:30 and 4:30;
//  - painted panels open to a cold night sky show S1 < 0 (emission-dominated); a warm object
//  filling
//    the specular direction (the paper's plastic pool) reflects into them with the opposite
//    polarization and cancels most of that contrast.

#include <gtest/gtest.h>

#include <cmath>

#include "scene_fixtures.h"

namespace tirpol::simulation {
namespace {

using tirpol::test::TempDir;

TEST(BallPhenomenology, EmissionIsPolarizedRadially) {
    TempDir dir;
    const Scene scene = test::load_scene_text(
        dir,
        test::scene_header(33, 33, 8, 2, "fov_deg: 30, position: [0, -5, 0], look_at: [0, 0, 0]",
                           "{type: clear_sky, air_temperature: 270, zenith_emissivity: 0.7}") +
            "objects:\n  - {name: ball, geometry: {type: sphere, radius: 1}, material: " +
            test::kSmoothPaint + ", temperature: 300}\n");
    const Image img = render(scene);
    // Ball radius in pixels: f·atan(1/5)… ≈ 0.2 rad · 61.6 px/rad ≈ 12 px; sample at 0.8 of it.
    const double c = 16.5, r = 0.8 * 12.0;
    auto at = [&](const char* ch, double clock_hours) {
        const double a = deg_to_rad(
            90.0 - 30.0 * clock_hours);  // angle from +x, counter-clockwise; up = −y in rows
        const int x = static_cast<int>(c + r * std::cos(a)),
                  y = static_cast<int>(c - r * std::sin(a));
        return img.at(ch, x, y);
    };
    for (double h : {0.0, 6.0}) EXPECT_LT(at("S1", h), 0.0) << h << " o'clock";
    for (double h : {3.0, 9.0}) EXPECT_GT(at("S1", h), 0.0) << h << " o'clock";
    for (double h : {1.5, 7.5}) EXPECT_GT(at("S2", h), 0.0) << h << " o'clock";
    for (double h : {4.5, 10.5}) EXPECT_LT(at("S2", h), 0.0) << h << " o'clock";
    // Extremes: |S1| at 12 o'clock exceeds |S1| at 1:30 (where S2 takes over), and vice versa.
    EXPECT_GT(std::abs(at("S1", 0.0)), 3.0 * std::abs(at("S1", 1.5)));
    EXPECT_GT(std::abs(at("S2", 1.5)), 3.0 * std::abs(at("S2", 0.0)));
}

/// A smooth panel tilted 40° toward the camera, seen at a grazing-ish angle; optionally a warm box
/// ("pool") filling the specular direction.
double panel_s1(bool with_pool) {
    TempDir dir;
    std::string yaml =
        test::scene_header(16, 12, 32, 3,
                           "fov_deg: 6, position: [0, -6, 2.5], look_at: [0, 0, 0.5]",
                           "{type: clear_sky, air_temperature: 275, zenith_emissivity: 0.65}") +
        "objects:\n  - {name: panel, geometry: {type: plane, size: [2, 2]}, transform: {translate: "
        "[0, 0, 0.5], rotate_deg: [20, 0, 0]}, material: " +
        test::kSmoothPaint + ", temperature: 280}\n";
    if (with_pool)
        yaml +=
            "  - {name: pool, geometry: {type: box, size: [30, 1, 60]}, transform: {translate: [0, "
            "12, 0]}, material: "
            "{name: pool_plastic, source: test, model: lambertian, parameters: {reflectance: "
            "0.05}}, temperature: 282}\n";
    const Image img = render(test::load_scene_text(dir, yaml));
    double sum = 0.0;
    for (int y = 4; y < 8; ++y)
        for (int x = 6; x < 10; ++x) sum += img.at("S1", x, y);
    return sum / 16.0;
}

TEST(PoolCancellation, WarmObjectInTheSpecularDirectionCancelsPanelContrast) {
    const double open_sky = panel_s1(false), with_pool = panel_s1(true);
    EXPECT_LT(open_sky, 0.0) << "panel under a cold sky: emission-dominated, vertical";
    EXPECT_LT(std::abs(with_pool), 0.3 * std::abs(open_sky))
        << "open sky " << open_sky << ", with pool " << with_pool;
}

}  // namespace
}  // namespace tirpol::simulation
