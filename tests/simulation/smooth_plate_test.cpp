// A flat smooth plate under a uniform sky (paper eq 17 without the polarizer, and Sandus, Appl.
// Opt. 4, 1634, 1965): the camera sees S0 = ε(θ)·L_bb(T_plate) + (1 − ε(θ))·L_sky and S1 =
// ε₁(θ)·(L_bb(T_plate) − L_sky), band-integrated, with ε from the materials module
// (directional_emissivity). Stokes sign (ARCHITECTURE.md): an emission-dominated plate is polarized
// vertically in the image (S1 < 0), a reflection-dominated one horizontally (S1 > 0).

#include <gtest/gtest.h>

#include <cmath>

#include "scene_fixtures.h"
#include "tirpol/materials/emissivity.h"

namespace tirpol::simulation {
namespace {

using tirpol::test::TempDir;

struct PlateCase {
    double view_zenith_deg, plate_k, sky_k;
};

void check_plate(const PlateCase& c) {
    TempDir dir;
    const double th = deg_to_rad(c.view_zenith_deg), d = 5.0;
    const std::string camera =
        fmt::format("fov_deg: 0.2, position: [0, {}, {}], look_at: [0, 0, 0]", -d * std::sin(th),
                    d * std::cos(th));
    const Scene scene = test::load_scene_text(
        dir,
        test::scene_header(5, 5, 256, 4, camera,
                           fmt::format("{{type: uniform, temperature: {}}}", c.sky_k)) +
            "objects:\n  - {name: plate, geometry: {type: plane, size: [400, 400]}, material: " +
            test::kSmoothPaint + fmt::format(", temperature: {}}}\n", c.plate_k));
    const Image img = render(scene);

    const auto& brdf = *scene.materials[0].brdf;
    double s0 = 0.0, s1 = 0.0;
    for (const auto& node : scene.band.nodes()) {
        const StokesVector eps =
            materials::directional_emissivity(brdf, std::cos(th), node.wavelength_um);
        const double lp = planck_radiance(node.wavelength_um, c.plate_k),
                     ls = planck_radiance(node.wavelength_um, c.sky_k);
        s0 += node.weight_um * (eps[0] * lp + (1.0 - eps[0]) * ls);
        s1 += node.weight_um * eps[1] * (lp - ls);
    }
    const double tol0 = 5.0 * std::sqrt(img.at("S0_var", 2, 2)) + 1e-4 * s0;
    const double tol1 = 5.0 * std::sqrt(img.at("S1_var", 2, 2)) + 1e-4 * s0;
    EXPECT_NEAR(img.at("S0", 2, 2), s0, tol0) << "θ = " << c.view_zenith_deg;
    EXPECT_NEAR(img.at("S1", 2, 2), s1, tol1) << "θ = " << c.view_zenith_deg;
    EXPECT_NEAR(img.at("S2", 2, 2), 0.0, 5.0 * std::sqrt(img.at("S2_var", 2, 2)) + 1e-6 * s0);
    if (c.plate_k > c.sky_k) {
        EXPECT_LT(img.at("S1", 2, 2), 0.0) << "emission-dominated: vertical polarization";
        EXPECT_NEAR(img.at("AoP", 2, 2), 90.0, 0.5);
    } else {
        EXPECT_GT(img.at("S1", 2, 2), 0.0) << "reflection-dominated: horizontal polarization";
    }
    EXPECT_NEAR(img.at("view_zenith_deg", 2, 2), c.view_zenith_deg, 0.05);
}

TEST(SmoothPlate, WarmPlateUnderColdSkyIsVerticallyPolarized) {
    check_plate({60.0, 300.0, 230.0});
    check_plate({75.0, 300.0, 230.0});
}

TEST(SmoothPlate, ColdPlateUnderWarmSkyIsHorizontallyPolarized) {
    check_plate({70.0, 260.0, 300.0});
}

}  // namespace
}  // namespace tirpol::simulation
