// Honest per-pixel error bars (issue 13): the S0_var/S1_var/S2_var channels are the variance of the
// pixel's mean, so in an isothermal enclosure — where the exact answer is known, S = (L_bb, 0, 0, 0)
// by Kirchhoff's law (paper eq 5) — z = (S − exact)/√var must follow the distribution that the
// estimator implies. The renderer's variance is the spread of R i.i.d. replicate means (renderer.h),
// an unbiased estimate with ν = R − 1 degrees of freedom (the image's `variance_dof`): for replicate
// means close to Gaussian, z follows Student's t with ν dof, whose tails are heavier than a Gaussian's
// (P(|t₁₅| > 5) = 1.6e-4 against 5.7e-7; P(|t₁₅| > 3) = 0.90 % against 0.27 %) and E z² = ν/(ν − 2).
// The thresholds below are derived from ν (expect_student_t_z). Heavy-tailed sample weights break
// this long before they bias the image mean: a pixel's few rare, huge samples are absent from most
// replicates, whose spread then understates the error.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <variant>

#include "scene_fixtures.h"

namespace tirpol::simulation {
namespace {

using tirpol::test::TempDir;

struct ZStatistics {
    std::size_t values = 0, beyond3 = 0, beyond5 = 0;
    double max_abs_z = 0.0, mean_z2 = 0.0;
};

ZStatistics z_statistics(const Image& img, double l_bb) {
    ZStatistics z;
    const char* value_channels[] = {"S0", "S1", "S2"};
    const char* variance_channels[] = {"S0_var", "S1_var", "S2_var"};
    for (std::size_t i = 0; i < img.pixel_count(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double exact = c == 0 ? l_bb : 0.0;
            const double var = img.channel(variance_channels[c])[i];
            const double value = img.channel(value_channels[c])[i];
            // Pixels whose paths are deterministic (mirror → uniform sky) have var ≈ 0 and S1, S2 of
            // ~1e-9·L_bb from rounding where emission and reflection cancel: floor σ at 1e-6·L_bb, 16×
            // the float32 resolution of the stored S0.
            const double zi = (value - exact) / std::sqrt(var + 1e-12 * l_bb * l_bb);
            ++z.values;
            z.beyond3 += std::abs(zi) > 3.0 ? 1 : 0;
            z.beyond5 += std::abs(zi) > 5.0 ? 1 : 0;
            z.max_abs_z = std::max(z.max_abs_z, std::abs(zi));
            z.mean_z2 += zi * zi;
        }
    z.mean_z2 /= static_cast<double>(std::max<std::size_t>(1, z.values));
    return z;
}

/// P(|T| > x) for Student's t with ν degrees of freedom: ∫_x^∞ of its density, by the midpoint rule in
/// u = x/t ∈ (0, 1] (smooth there; 1e-6 relative at the x and ν used here).
double student_t_two_sided_tail(double x, double nu) {
    const double c = std::exp(std::lgamma((nu + 1.0) / 2.0) - std::lgamma(nu / 2.0)) / std::sqrt(nu * std::numbers::pi);
    constexpr int kSteps = 20000;
    double sum = 0.0;
    for (int i = 0; i < kSteps; ++i) {
        const double u = (i + 0.5) / kSteps, t = x / u;
        sum += c * std::pow(1.0 + t * t / nu, -(nu + 1.0) / 2.0) * x / (u * u);
    }
    return 2.0 * sum / kSteps;
}

double variance_dof(const Image& img) { return static_cast<double>(std::get<int>(img.attributes().at("variance_dof"))); }

/// z must look like Student's t with ν dof. The counts' own scatter is allowed for with the pixel count
/// (a pixel's S0, S1 and S2 share its replicates, so they are not independent values): a count of
/// expected mean μ = n·p is allowed μ + 5√μ; mean z², E = ν/(ν − 2) with Var(t²) = 2ν²(ν − 1)/((ν − 2)²(ν − 4)),
/// is allowed E + 5·√(Var/pixels). Independent of that, the project's requirement: |z| > 5 in < 0.1 %.
void expect_student_t_z(const ZStatistics& z, double nu, const std::string& what) {
    const double n = static_cast<double>(z.values), pixels = n / 3.0;
    ASSERT_GT(z.values, 1000u) << what;
    ASSERT_GT(nu, 4.0) << what;
    std::printf("%s: %zu z-values, ν = %g, |z| > 3: %.3f %% (t: %.3f %%), |z| > 5: %.3f %% (t: %.4f %%), max |z| %.2f, "
                "mean z² %.3f (t: %.3f)\n",
                what.c_str(), z.values, nu, 100.0 * static_cast<double>(z.beyond3) / n,
                100.0 * student_t_two_sided_tail(3.0, nu), 100.0 * static_cast<double>(z.beyond5) / n,
                100.0 * student_t_two_sided_tail(5.0, nu), z.max_abs_z, z.mean_z2, nu / (nu - 2.0));
    EXPECT_LT(static_cast<double>(z.beyond5), 1e-3 * n) << what << ": |z| > 5";
    const double expected3 = n * student_t_two_sided_tail(3.0, nu);
    EXPECT_LT(static_cast<double>(z.beyond3), expected3 + 5.0 * std::sqrt(expected3)) << what << ": |z| > 3";
    const double mean_t2 = nu / (nu - 2.0);
    const double var_t2 = 2.0 * nu * nu * (nu - 1.0) / ((nu - 2.0) * (nu - 2.0) * (nu - 4.0));
    // Too small variances show as mean z² ≫ E; too large ones (a conservative estimator) as ≪ E.
    EXPECT_NEAR(z.mean_z2, mean_t2, 5.0 * std::sqrt(var_t2 / pixels)) << what;
}

/// A mirror tilted 95° about x at y = 1 reflects the camera's horizontal view down onto a glossy paint
/// ground seen 75–85° off its normal: the geometry of the 36–71σ pixels. Everything at 290 K.
std::string mirror_over_glossy_paint(const std::string& mirror, const std::string& paint, int spp) {
    return test::scene_header(48, 36, spp, 32, "fov_deg: 30, position: [0, -3, 1.0], look_at: [0, 1, 1.0]",
                              "{type: uniform, temperature: 290}") +
           "objects:\n"
           "  - {name: ground, geometry: {type: plane, size: [30, 30]}, material: " + paint + ", temperature: 290}\n"
           "  - {name: mirror, geometry: {type: plane, size: [4, 3]}, transform: {translate: [0, 1, 1.0], rotate_deg: [95, 0, 0]}, "
           "material: " + mirror + ", temperature: 290}\n";
}

TEST(ErrorBars, MirrorViewingGlossyPaintHasStudentTZScores) {
    TempDir dir;
    const Scene scene = test::load_scene_text(dir, mirror_over_glossy_paint("specular_gold_reflector", "glossy_black_paint", 256));
    const Image img = render(scene, test::without_control_variate());
    expect_student_t_z(z_statistics(img, scene.band.radiance(290.0)), variance_dof(img),
                       "gold mirror over glossy black paint, 256 spp");
}

/// A metal mirror (n = 12 + 60i, R ≈ 0.99 in the LWIR): a pure delta reflection.
const char* kMetalMirror =
    "{name: metal_mirror, source: test, model: smooth_fresnel, refractive_index: {n: 12, k: 60}}";

TEST(ErrorBars, MirrorViewingRoughPaintHasStudentTZScores) {
    TempDir dir;
    const char* paint = "{name: rough, source: test, model: microfacet, refractive_index: {n: 1.6, k: 0.1}, "
                        "parameters: {sigma: 0.2, bias: 0.1, tau_deg: 20, omega_deg: 60, rho_d: 0.05, rho_v: 0.02}}";
    const Scene scene = test::load_scene_text(dir, mirror_over_glossy_paint(kMetalMirror, paint, 128));
    const Image img = render(scene, test::without_control_variate());
    expect_student_t_z(z_statistics(img, scene.band.radiance(290.0)), variance_dof(img),
                       "metal mirror over rough Beard–Maxwell paint, 128 spp");
}

// Every library material as the ground of the mirror scene above (seen through the mirror 75–85° off
// its normal), isothermal, plain estimator, 64 spp: 16 replicates of 4 points, so the variance has
// ν = 15 degrees of freedom. What the estimator promises is calibration: mean z² = ν/(ν − 2) = 1.154 per
// material (Var z² over the pixels as in expect_student_t_z). The tails also depend on the integrand:
// a reflection drawn rarely (a lobe, or a masked facet: 3–7 % of the visible normals at 75–85° reflect
// below the horizon, bare_aluminium and diffuse_ir_reflector) can be missed by all 16 replicates of a
// pixel, which then reads high with a spread blind to it. Measured (docs/simulation.md): 0.31 % and
// 0.23 % of those two materials' values beyond 5, ≤ 0.08 % for every other one, 0.06 % over all. So the
// requirement |z| > 5 in < 0.1 % holds over all materials' values together, per material < 0.5 %, and
// no |z| ≥ 12 (P(|t₁₅| > 12) = 4.3e-9: one among 93 312 values has a chance of 4e-4 if the error bars
// are honest). Before the defensive lobe mixture and the folded masked reflections: bare aluminium
// 1.1 % beyond 5 and max |z| 14.3, glossy black paint max 37.0, clear coat max 27.6.
TEST(ErrorBars, EveryLibraryMaterialSeenInAMirrorHasCalibratedZScores) {
    TempDir dir;
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(tirpol::test::source_dir() / "config" / "materials"))
        if (entry.path().extension() == ".yaml") files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    ASSERT_GT(files.size(), 10u);
    std::size_t values = 0, beyond5 = 0;
    for (const auto& file : files) {
        const Scene scene = test::load_scene_text(dir, mirror_over_glossy_paint(kMetalMirror, file.string(), 64));
        const Image img = render(scene, test::without_control_variate());
        const double nu = variance_dof(img);
        ASSERT_EQ(nu, 15.0);
        const ZStatistics z = z_statistics(img, scene.band.radiance(290.0));
        const std::string what = file.stem().string() + " seen in a metal mirror, 64 spp";
        std::printf("%s: |z| > 5: %zu of %zu values, max |z| %.2f, mean z² %.3f\n", what.c_str(), z.beyond5, z.values,
                    z.max_abs_z, z.mean_z2);
        values += z.values;
        beyond5 += z.beyond5;
        // Smooth materials (ice, water, glass, gold) give deterministic paths whose z is rounding over the
        // 1e-6·L_bb floor: mean z² ≪ 1 there, which says nothing about the estimator.
        const double var_t2 = 2.0 * nu * nu * (nu - 1.0) / ((nu - 2.0) * (nu - 2.0) * (nu - 4.0));
        EXPECT_LT(z.mean_z2, nu / (nu - 2.0) + 5.0 * std::sqrt(var_t2 / (static_cast<double>(z.values) / 3.0))) << what;
        EXPECT_LT(static_cast<double>(z.beyond5), 5e-3 * static_cast<double>(z.values)) << what;
        EXPECT_LT(z.max_abs_z, 12.0) << what;
    }
    std::printf("all materials: |z| > 5: %zu of %zu values\n", beyond5, values);
    EXPECT_LT(static_cast<double>(beyond5), 1e-3 * static_cast<double>(values));
}

}  // namespace
}  // namespace tirpol::simulation
