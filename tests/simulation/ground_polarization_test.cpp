// Ground materials are polarized (paper §4 phenomenology; Sandus, Appl. Opt. 4, 1634 (1965)): a
// warm horizontal ground under a cold night sky, seen obliquely, is emission-dominated and so
// polarized in its plane of emission, vertically in the image: S1 < 0 in the camera frame
// (ARCHITECTURE.md). For a flat ground under a uniform sky the value is exact per wavelength
// (Kirchhoff, emissivity.h): S = ε(θ)·L_bb(T_ground) + (e0 − ε(θ))·L_sky, so S1 =
// ε₁(θ)·(L_bb(T_ground) − L_sky).

#include <gtest/gtest.h>

#include <cmath>

#include "scene_fixtures.h"
#include "tirpol/materials/emissivity.h"

namespace tirpol::simulation {
namespace {

using tirpol::test::TempDir;

class GroundMaterial : public ::testing::TestWithParam<std::string> {};

TEST_P(GroundMaterial, ObliqueGroundEmissionIsVerticallyPolarized) {
    TempDir dir;
    const double view_zenith_deg = 70.0, ground_k = 290.0, sky_k = 230.0;
    const double th = deg_to_rad(view_zenith_deg), d = 5.0;
    const std::string camera =
        fmt::format("fov_deg: 0.5, position: [0, {}, {}], look_at: [0, 0, 0]", -d * std::sin(th),
                    d * std::cos(th));
    const Scene scene = test::load_scene_text(
        dir,
        test::scene_header(4, 4, 256, 8, camera,
                           fmt::format("{{type: uniform, temperature: {}}}", sky_k)) +
            "objects:\n  - {name: ground, geometry: {type: plane, size: [400, 400]}, material: " +
            GetParam() + fmt::format(", temperature: {}}}\n", ground_k));
    RenderOptions options;
    options.emissivity_cache_dir = std::filesystem::path{};
    const Image img = render(scene, options);

    double s1 = 0.0, var = 0.0;
    for (std::size_t i = 0; i < img.pixel_count(); ++i) {
        s1 += img.channel("S1")[i];
        var += img.channel("S1_var")[i];
    }
    const auto n = static_cast<double>(img.pixel_count());
    s1 /= n;
    const double sigma = std::sqrt(var) / n;

    const auto& brdf = *scene.materials[0].brdf;
    double expected_s1 = 0.0, s0 = 0.0;
    for (const auto& node : scene.band.nodes()) {
        const StokesVector eps =
            materials::directional_emissivity(brdf, std::cos(th), node.wavelength_um);
        const double lg = planck_radiance(node.wavelength_um, ground_k),
                     ls = planck_radiance(node.wavelength_um, sky_k);
        expected_s1 += node.weight_um * eps[1] * (lg - ls);
        s0 += node.weight_um * (eps[0] * lg + (1.0 - eps[0]) * ls);
    }
    EXPECT_LT(s1 + 5.0 * sigma, 0.0) << GetParam() << ": S1 = " << s1 << " ± " << sigma;
    EXPECT_LT(expected_s1, -2e-3 * s0) << GetParam() << ": DoLP of at least 0.2 % expected at 70°";
    EXPECT_NEAR(s1, expected_s1, 5.0 * sigma + 1e-3 * s0) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(LibraryGrounds, GroundMaterial,
                         ::testing::Values("asphalt", "concrete", "leaf", "bark"));

}  // namespace
}  // namespace tirpol::simulation
