// Every output Stokes vector is physically realizable (S0 ≥ √(S1²+S2²+S3²), finite), and the degree
// of linear polarization of a smooth sphere varies smoothly up to grazing angles along its limb: it
// follows the Fresnel emission DoLP |ε₁|/ε₀ of the materials module at each pixel's view angle,
// with no salt-and-pepper outliers (the artifact the paper reports on the SUV roof, §4).

#include <gtest/gtest.h>

#include <cmath>

#include "scene_fixtures.h"
#include "tirpol/materials/emissivity.h"

namespace tirpol::simulation {
namespace {

using tirpol::test::TempDir;

TEST(Realizability, EveryPixelFiniteAndRealizableInADaytimeScene) {
    TempDir dir;
    const Scene scene = test::load_scene_text(
        dir, test::scene_header(
                 24, 18, 8, 4, "fov_deg: 40, position: [0, -4, 1.2], look_at: [0, 0, 0.4]",
                 "{type: clear_sky, air_temperature: 285, zenith_emissivity: 0.75}") +
                 "sun: {elevation_deg: 18, azimuth_deg: 160}\n"
                 "objects:\n"
                 "  - {name: ground, geometry: {type: plane, size: [10, 10]}, material: " +
                 test::kGreyDiffuse +
                 ", temperature: 280}\n"
                 "  - {name: ball, geometry: {type: sphere, radius: 0.5}, transform: {translate: "
                 "[0, 0, 0.5]}, material: " +
                 test::kSmoothPaint +
                 ", temperature: 300}\n"
                 "  - {name: panel, geometry: {type: box, size: [3, 0.1, 2]}, transform: "
                 "{translate: [0, 1.5, 1]}, material: "
                 "{name: rough, source: test, model: microfacet, refractive_index: {n: 1.6, k: "
                 "0.1}, parameters: {sigma: 0.1, bias: 0.1, "
                 "tau_deg: 20, omega_deg: 60, rho_d: 0.05, rho_v: 0.02}}, temperature: 290}\n");
    const Image img = render(scene);
    for (std::size_t i = 0; i < img.pixel_count(); ++i) {
        const StokesVector s(img.channel("S0")[i], img.channel("S1")[i], img.channel("S2")[i],
                             img.channel("S3")[i]);
        ASSERT_TRUE(s.allFinite()) << "pixel " << i;
        ASSERT_TRUE(is_realizable(s, 1e-5)) << "pixel " << i << ": " << s.transpose();
        for (const char* ch : {"DoLP", "AoP", "S0_var", "S1_var", "S2_var"})
            ASSERT_TRUE(std::isfinite(img.channel(ch)[i])) << ch;
    }
}

TEST(Realizability, SmoothSphereDoLPIsSmoothUpToTheLimb) {
    TempDir dir;
    // A sky at 3 K: the camera sees emission only, whose DoLP is |ε₁|/ε₀ at the view angle (a pixel
    // that straddles the limb mixes sphere and a black sky, which scales S0 and S1 alike).
    const Scene scene = test::load_scene_text(
        dir,
        test::scene_header(48, 48, 4, 1, "fov_deg: 26, position: [0, -5, 0], look_at: [0, 0, 0]",
                           "{type: uniform, temperature: 3}") +
            "objects:\n  - {name: ball, geometry: {type: sphere, radius: 1}, material: " +
            test::kSmoothPaint + ", temperature: 300}\n");
    const Image img = render(scene);
    const materials::EmissivityTable table(
        *scene.materials[0].brdf, materials::EmissivityTable::wavelengths_for_band(scene.band),
        129);
    std::size_t on_sphere = 0, outliers = 0, grazing = 0;
    for (std::size_t i = 0; i < img.pixel_count(); ++i) {
        const double vz = img.channel("view_zenith_deg")[i];
        if (!std::isfinite(vz) || vz > 89.5) continue;
        ++on_sphere;
        if (vz > 75.0) ++grazing;
        // Band DoLP of the emission: |∫R L_bb ε₁ dλ| / ∫R L_bb ε₀ dλ.
        const StokesVector e = table.band_average(std::cos(deg_to_rad(vz)), scene.band, 300.0);
        const double expected = std::abs(e[1]) / e[0];
        // Pixel footprint spans a range of view angles near the limb: allow 0.05 in DoLP.
        if (std::abs(img.channel("DoLP")[i] - expected) > 0.05) ++outliers;
    }
    ASSERT_GT(on_sphere, 500u);
    EXPECT_GT(grazing, 40u) << "the test must reach grazing angles";
    EXPECT_LE(static_cast<double>(outliers), 0.02 * static_cast<double>(on_sphere))
        << outliers << " of " << on_sphere;
}

}  // namespace
}  // namespace tirpol::simulation
