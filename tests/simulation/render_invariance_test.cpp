// Invariances of the renderer: the image does not depend on the thread count or the tiling
// (counter-based random numbers per pixel and sample), and the physics does not depend on the
// azimuth: rotating the scene and the camera together about the vertical leaves the image unchanged
// within its Monte-Carlo error (the sky depends on zenith angle only; Stokes is expressed in the
// camera frame, which rotates with the scene).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "scene_fixtures.h"
#include "tirpol/core/error.h"

namespace tirpol::simulation {
namespace {

using tirpol::test::TempDir;

/// Ball on diffuse ground before a tilted smooth panel, rotated by `yaw_deg` about the world z
/// axis.
std::string rotated_scene(double yaw_deg) {
    const Mat3 r = Eigen::AngleAxisd(deg_to_rad(yaw_deg), Vec3::UnitZ()).toRotationMatrix();
    const auto p = [&](double x, double y, double z) {
        const Vec3 v = r * Vec3(x, y, z);
        return fmt::format("[{:.12g}, {:.12g}, {:.12g}]", v.x(), v.y(), v.z());
    };
    return test::scene_header(
               24, 18, 6, 3,
               "fov_deg: 35, position: " + p(0.3, -4, 1.5) + ", look_at: " + p(0, 0, 0.5),
               "{type: clear_sky, air_temperature: 280, zenith_emissivity: 0.7}") +
           "objects:\n"
           "  - {name: ground, geometry: {type: disk, radius: 8, segments: 64}, transform: "
           "{rotate_deg: [0, 0, " +
           fmt::format("{}", yaw_deg) + "]}, material: " + test::kGreyDiffuse +
           ", temperature: 285}\n" +
           "  - {name: ball, geometry: {type: sphere, radius: 0.5}, transform: {translate: " +
           p(0, 0, 0.5) + "}, material: " + test::kSmoothPaint + ", temperature: 300}\n" +
           "  - {name: panel, geometry: {type: box, size: [3, 0.1, 2]}, transform: {translate: " +
           p(0, 1.5, 1) + ", rotate_deg: [-15, 0, " + fmt::format("{}", yaw_deg) +
           "]}, material: " + test::kSmoothPaint + ", temperature: 290}\n";
}

TEST(RenderInvariance, SameImageForOneAndTwoThreadsAndAnyTiling) {
    TempDir dir;
    const Scene scene = test::load_scene_text(dir, rotated_scene(0.0));
    RenderOptions one, two;
    one.threads = 1;
    two.threads = 2;
    two.tile_size = 5;
    const Image a = render(scene, one), b = render(scene, two);
    for (const auto& name : a.channel_names()) {
        const auto& pa = a.channel(name);
        const auto& pb = b.channel(name);
        for (std::size_t i = 0; i < pa.size(); ++i)
            ASSERT_TRUE(pa[i] == pb[i] || (std::isnan(pa[i]) && std::isnan(pb[i])))
                << name << " pixel " << i;
    }
}

// A pixel mask (what the fit through the renderer uses to trace only its regions) leaves the traced
// pixels bit-identical to the full render and NaN elsewhere; a mask of the wrong size is an error.
TEST(RenderInvariance, MaskedPixelsAreTheFullRendersAndTheRestIsNaN) {
    TempDir dir;
    const Scene scene = test::load_scene_text(dir, rotated_scene(0.0));
    const Image full = render(scene);
    std::vector<std::uint8_t> mask(
        static_cast<std::size_t>(full.width()) * static_cast<std::size_t>(full.height()), 0);
    for (std::size_t i = 0; i < mask.size(); i += 7) mask[i] = 1;
    RenderOptions masked;
    masked.pixel_mask = &mask;
    masked.tile_size = 5;
    const Image part = render(scene, masked);
    for (const auto& name : full.channel_names()) {
        const auto& pf = full.channel(name);
        const auto& pp = part.channel(name);
        for (std::size_t i = 0; i < pf.size(); ++i) {
            if (mask[i])
                ASSERT_TRUE(pf[i] == pp[i] || (std::isnan(pf[i]) && std::isnan(pp[i])))
                    << name << " pixel " << i;
            else
                ASSERT_TRUE(std::isnan(pp[i])) << name << " pixel " << i << " outside the mask";
        }
    }
    mask.pop_back();
    try {
        render(scene, masked);
        FAIL() << "a mask of the wrong size was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("pixel mask has"), std::string::npos) << e.what();
    }
}

TEST(RenderInvariance, RotatingSceneAndCameraAboutTheVerticalLeavesTheImageUnchanged) {
    TempDir dir;
    // Per-pixel 5σ comparisons: per-pixel error bars (test::with_per_pixel_error_bars).
    const Image a = render(
        test::with_per_pixel_error_bars(test::load_scene_text(dir, rotated_scene(0.0), "a.yaml")));
    const Image b = render(
        test::with_per_pixel_error_bars(test::load_scene_text(dir, rotated_scene(37.0), "b.yaml")));
    // The tangent frames in which the pBRDFs are sampled do not rotate with the scene, so the two
    // renders are independent Monte-Carlo estimates of the same image: compare them per pixel with
    // their reported errors (|a − b| ≤ 5·√(σa² + σb²)), allowing 1 % outliers for silhouette pixels
    // and heavy-tailed samples.
    for (const char* ch : {"S0", "S1", "S2"}) {
        const auto& pa = a.channel(ch);
        const auto& pb = b.channel(ch);
        const auto& va = a.channel(std::string(ch) + "_var");
        const auto& vb = b.channel(std::string(ch) + "_var");
        std::size_t off = 0;
        double sum_diff = 0.0, sum_var = 0.0;
        for (std::size_t i = 0; i < pa.size(); ++i) {
            if (std::abs(pa[i] - pb[i]) > 5.0 * std::sqrt(va[i] + vb[i]) + 1e-6) ++off;
            sum_diff += pa[i] - pb[i];
            sum_var += va[i] + vb[i];
        }
        EXPECT_LE(static_cast<double>(off), 0.01 * static_cast<double>(pa.size()))
            << ch << ": " << off << " pixels differ";
        EXPECT_LE(std::abs(sum_diff), 5.0 * std::sqrt(sum_var)) << ch << ": image means differ";
    }
    // Geometry channels are deterministic: the same up to float rounding.
    std::size_t depth_off = 0;
    for (std::size_t i = 0; i < a.pixel_count(); ++i) {
        const float da = a.channel("depth")[i], db = b.channel("depth")[i];
        if (!(std::abs(da - db) < 1e-3f || (std::isnan(da) && std::isnan(db)))) ++depth_off;
    }
    EXPECT_LE(depth_off, a.pixel_count() / 100) << "depth differs beyond rounding";
}

}  // namespace
}  // namespace tirpol::simulation
