// Kirchhoff's law in an isothermal enclosure (paper eq 5; ARCHITECTURE.md "Physics to get right"):
// when every surface and the sky are at one temperature T, the radiance leaving any surface is the
// blackbody radiance L_bb(T), unpolarized, whatever the material — emission ε(θ) and reflection
// ∫M cosθi dωi add up to e0 exactly. Each pixel must give S0 = L_bb(T), S1 = S2 = S3 = 0 within its
// reported Monte-Carlo error.

#include <gtest/gtest.h>

#include <cmath>

#include "scene_fixtures.h"

namespace tirpol::simulation {
namespace {

using tirpol::test::TempDir;

/// Ball on a ground plate in front of a wall, open to the sky, everything at 290 K, one material.
std::string enclosure_scene(const std::string& material) {
    return test::scene_header(20, 14, 24, 12, "fov_deg: 40, position: [0, -4, 1.2], look_at: [0, 0, 0.4]",
                              "{type: uniform, temperature: 290}") +
           "objects:\n"
           "  - {name: ground, geometry: {type: plane, size: [6, 6]}, material: " + material + ", temperature: 290}\n"
           "  - {name: wall, geometry: {type: box, size: [4, 0.2, 2]}, transform: {translate: [0, 1.5, 1], rotate_deg: [0, 0, 20]}, material: " +
           material + ", temperature: 290}\n"
           "  - {name: ball, geometry: {type: sphere, radius: 0.5}, transform: {translate: [0, 0, 0.5]}, material: " + material +
           ", temperature: 290}\n";
}

void expect_blackbody(const Image& img, double l_bb, const std::string& what) {
    int failures = 0;
    double mean_s0 = 0.0;
    for (int y = 0; y < img.height(); ++y) {
        for (int x = 0; x < img.width(); ++x) {
            const double s0 = img.at("S0", x, y);
            mean_s0 += s0;
            // 5σ of the reported variance of the mean, plus 2e-4·L for the emissivity table's
            // interpolation and quadrature error (materials/emissivity.h: |Δε| < 2e-4).
            const double tol0 = 5.0 * std::sqrt(img.at("S0_var", x, y)) + 2e-4 * l_bb;
            const double tol1 = 5.0 * std::sqrt(img.at("S1_var", x, y)) + 2e-4 * l_bb;
            const double tol2 = 5.0 * std::sqrt(img.at("S2_var", x, y)) + 2e-4 * l_bb;
            const bool ok = std::abs(s0 - l_bb) <= tol0 && std::abs(img.at("S1", x, y)) <= tol1 &&
                            std::abs(img.at("S2", x, y)) <= tol2 && std::abs(img.at("S3", x, y)) <= 2e-4 * l_bb + tol1;
            if (!ok && ++failures <= 3)
                ADD_FAILURE() << what << " pixel (" << x << "," << y << "): S = (" << s0 << ", " << img.at("S1", x, y)
                              << ", " << img.at("S2", x, y) << ", " << img.at("S3", x, y) << "), expected (" << l_bb
                              << ", 0, 0, 0) ± (" << tol0 << ", " << tol1 << ", " << tol2 << ")";
        }
    }
    mean_s0 /= static_cast<double>(img.pixel_count());
    EXPECT_EQ(failures, 0) << what;
    // The mean over all pixels is a much tighter check on bias (spectral-node sampling noise averages out).
    EXPECT_NEAR(mean_s0 / l_bb, 1.0, 3e-3) << what;
}

TEST(IsothermalEnclosure, InlineModelsRenderTheBlackbody) {
    TempDir dir;
    for (const char* material : {test::kSmoothPaint, test::kGreyDiffuse,
                                 "{name: rough, source: test, model: microfacet, refractive_index: {n: 1.6, k: 0.1}, "
                                 "parameters: {sigma: 0.2, bias: 0.1, tau_deg: 20, omega_deg: 60, rho_d: 0.05, rho_v: 0.02}}"}) {
        const Scene scene = test::load_scene_text(dir, enclosure_scene(material));
        expect_blackbody(render(scene), scene.band.radiance(290.0), material);
    }
}

TEST(IsothermalEnclosure, EveryLibraryMaterialRendersTheBlackbody) {
    TempDir dir;
    const auto library = tirpol::test::source_dir() / "config" / "materials";
    int count = 0;
    for (const auto& entry : std::filesystem::directory_iterator(library)) {
        const auto ext = entry.path().extension();
        if (ext != ".yaml" && ext != ".yml") continue;
        ++count;
        const Scene scene = test::load_scene_text(dir, enclosure_scene(entry.path().string()));
        expect_blackbody(render(scene), scene.band.radiance(290.0), entry.path().filename().string());
    }
    EXPECT_GT(count, 0) << "no material files in " << library;
}

}  // namespace
}  // namespace tirpol::simulation
