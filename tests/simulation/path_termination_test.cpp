// Path termination by Russian roulette (renderer.h): unbiased however deep the reflections go. A
// closed box of bare aluminium (ε ≈ 0.01–0.02, Rakić 1995 index) at uniform temperature is a cavity
// in equilibrium: every ray from inside it must see L_bb(T) (Kirchhoff; Planck's cavity radiation).
// A path needs ~1/ε ≈ 50–100 reflections to collect it, so a fixed bounce limit darkens it badly.

#include <gtest/gtest.h>

#include <cmath>

#include "scene_fixtures.h"
#include "tirpol/core/error.h"

namespace tirpol::simulation {
namespace {

using tirpol::test::TempDir;

/// Camera inside a closed 3 × 3 × 2 m box of `material` at 300 K (the sky, never seen, is colder).
std::string aluminium_box(int max_bounces, const std::string& material = "bare_aluminium",
                          int spp = 64) {
    return test::scene_header(12, 8, spp, max_bounces,
                              "fov_deg: 40, position: [0.3, -0.9, 0.2], look_at: [0.5, 1, -0.3]",
                              "{type: uniform, temperature: 220}") +
           "objects:\n"
           "  - {name: box, geometry: {type: box, size: [3, 3, 2]}, material: " +
           material + ", temperature: 300}\n";
}

/// Polished aluminium: exact Fresnel reflection with the library's Rakić (1995) index, so sample
/// weights are the reflectance matrices (≤ 1) and only the path length is random.
std::string polished_aluminium() {
    return "{name: polished_aluminium, source: test, model: smooth_fresnel, refractive_index: "
           "{file: " +
           (tirpol::test::source_dir() / "config" / "materials" / "data" /
            "aluminium_rakic_1995.yml")
               .string() +
           "}}";
}

struct ImageMean {
    double s0 = 0.0,
           sigma = 0.0;  ///< mean S0 over the image and its standard error (pooled variances)
};

ImageMean mean_s0(const Image& img) {
    ImageMean m;
    double var_sum = 0.0;
    for (std::size_t i = 0; i < img.pixel_count(); ++i) {
        m.s0 += img.channel("S0")[i];
        var_sum += img.channel("S0_var")[i];
    }
    const auto n = static_cast<double>(img.pixel_count());
    m.s0 /= n;
    m.sigma = std::sqrt(var_sum) / n;
    return m;
}

TEST(PathTermination, ClosedPolishedAluminiumBoxIsABlackbodyInEveryPixel) {
    TempDir dir;
    const Scene scene = test::with_per_pixel_error_bars(
        test::load_scene_text(dir, aluminium_box(kDefaultMaxBounces, polished_aluminium(), 1536)));
    ASSERT_EQ(scene.sampling.max_bounces, kDefaultMaxBounces);
    const Image img = render(scene, test::without_control_variate());
    const double l_bb = scene.band.radiance(300.0);
    const ImageMean m = mean_s0(img);
    EXPECT_LE(std::abs(m.s0 - l_bb), 5.0 * m.sigma + 2e-3 * l_bb)
        << "image mean S0 = " << m.s0 << ", L_bb = " << l_bb << ", σ = " << m.sigma;
    EXPECT_LT(m.sigma, 0.01 * l_bb) << "too noisy to tell";
    // Every pixel: S0 = L_bb and S1 = S2 = 0 within 5σ of its own reported error.
    std::size_t outside = 0;
    for (std::size_t i = 0; i < img.pixel_count(); ++i)
        for (const auto& [channel, expected] :
             {std::pair{"S0", l_bb}, std::pair{"S1", 0.0}, std::pair{"S2", 0.0}}) {
            const double z = (img.channel(channel)[i] - expected) /
                             std::sqrt(img.channel(std::string(channel) + "_var")[i]);
            if (std::abs(z) > 5.0 && ++outside <= 3)
                ADD_FAILURE() << "pixel " << i << " " << channel << ": z = " << z << " value "
                              << img.channel(channel)[i] << " L_bb " << l_bb;
        }
    EXPECT_EQ(outside, 0u);
}

// The library's bare_aluminium is rough (σ = 0.1 facets): its sample weights are heavy-tailed, so
// the check is the image mean against its pooled error.
TEST(PathTermination, ClosedRoughAluminiumBoxConvergesToTheBlackbody) {
    TempDir dir;
    const Scene scene =
        test::load_scene_text(dir, aluminium_box(kDefaultMaxBounces, "bare_aluminium", 256));
    const double l_bb = scene.band.radiance(300.0);
    const ImageMean m = mean_s0(render(scene, test::without_control_variate()));
    EXPECT_LE(std::abs(m.s0 - l_bb), 5.0 * m.sigma + 2e-3 * l_bb)
        << "image mean S0 = " << m.s0 << ", L_bb = " << l_bb << ", σ = " << m.sigma;
    EXPECT_LT(m.sigma, 0.04 * l_bb) << "too noisy to tell";
}

// The same box with the bounce limit as the only termination (max_bounces: 4, the old default)
// loses most of the cavity radiance: the cap is a bias, which is why it is only a safety cap now.
TEST(PathTermination, ALowBounceCapTruncatesTheCavity) {
    TempDir dir;
    const Scene scene = test::load_scene_text(dir, aluminium_box(4));
    const ImageMean m = mean_s0(render(scene, test::without_control_variate()));
    EXPECT_LT(m.s0, 0.5 * scene.band.radiance(300.0));
}

TEST(PathTermination, BounceCapIsValidatedInTheSceneFile) {
    TempDir dir;
    for (int bad : {-1, kMaxBouncesLimit + 1}) {
        try {
            test::load_scene_text(dir, aluminium_box(bad));
            ADD_FAILURE() << bad << " accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("max_bounces"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("0–100000"), std::string::npos) << e.what();
        }
    }
    EXPECT_EQ(max_bounces_problem(0), "");
    EXPECT_EQ(max_bounces_problem(kMaxBouncesLimit), "");
}

}  // namespace
}  // namespace tirpol::simulation
