// Microgrid demosaicing and reduction against scenes whose full-resolution Stokes is known
// (microgrid_scenes.h, imaged by the ideal forward model microgrid_from_stokes): exactness where
// the interpolation has nothing to guess, the IFOV error of super-pixel on smooth fields, and the
// false DoLP that an unpolarized edge turns into, per method. The table that docs/microgrid.md
// quotes is printed by MicrogridAccuracy.TablePerMethod.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "microgrid_accuracy.h"
#include "microgrid_scenes.h"
#include "tirpol/calibration/microgrid_stokes.h"
#include "tirpol/core/error.h"

namespace tirpol::calibration {
namespace {

using testing::StokesScene;

constexpr DemosaicMethod kMethods[] = {DemosaicMethod::SuperPixel, DemosaicMethod::Bilinear,
                                       DemosaicMethod::Newton};

StokesErrors measure(const StokesScene& scene, DemosaicMethod method, bool edge_only,
                     int border_px = 4,
                     const MicrogridPattern& pattern = MicrogridPattern::sony_imx250mzr()) {
    const std::vector<float> mosaic =
        microgrid_from_stokes(scene.s0, scene.s1, scene.s2, scene.width, scene.height, pattern);
    MicrogridReductionOptions options;
    options.method = method;
    // Measure the demosaicing itself, not the projection of noise-free but IFOV-broken vectors.
    options.reduction.project_to_realizable = false;
    const Image stokes = reduce_microgrid(mosaic, scene.width, scene.height, pattern, options);
    return compare_to_truth(stokes, scene.s0, scene.s1, scene.s2, scene.width, scene.height,
                            border_px,
                            edge_only ? std::span<const unsigned char>(scene.edge_mask)
                                      : std::span<const unsigned char>());
}

TEST(MicrogridDemosaic, UniformPolarizedFieldDemosaicsExactlyWithEveryMethodAndPattern) {
    // A uniform field has no IFOV error: every method must return the scene's Stokes vector (to
    // float rounding), at every pixel including the borders, for any valid pattern.
    const StokesScene scene = testing::integrate_scene(16, 12, [](double, double) {
        return testing::StokesPoint{200.0, 36.0, -52.0};
    });
    for (const char* pattern : {"90,45,135,0", "0,45,90,135", "0,60,120,30"})
        for (DemosaicMethod method : kMethods) {
            const StokesErrors e =
                measure(scene, method, false, 0, MicrogridPattern::parse(pattern));
            EXPECT_LT(std::max({e.s0_rms, e.s1_rms, e.s2_rms}), 2e-4)
                << pattern << " " << demosaic_method_name(method);
            EXPECT_LT(e.dolp_max, 1e-6) << pattern << " " << demosaic_method_name(method);
        }
}

TEST(MicrogridDemosaic, PlanesFollowThePattern) {
    // Each pixel holds its analyzer's angle: every plane must come out constant at its own angle,
    // so a plane never takes samples from another analyzer (Sony layout: the 0° plane is fed by
    // (1,1)).
    const MicrogridPattern sony = MicrogridPattern::sony_imx250mzr();
    const int w = 8, h = 6;
    std::vector<float> mosaic(static_cast<std::size_t>(w * h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            mosaic[static_cast<std::size_t>(y * w + x)] =
                static_cast<float>(sony.angle_at_pixel_deg(x, y));
    for (DemosaicMethod method : kMethods) {
        const DemosaicedFrame frame = demosaic_microgrid(mosaic, w, h, sony, method);
        EXPECT_EQ(frame.width, method == DemosaicMethod::SuperPixel ? w / 2 : w);
        for (std::size_t c = 0; c < 4; ++c) {
            EXPECT_EQ(frame.angles_deg[c], sony.angles_deg()[c]);
            for (float v : frame.planes[c])
                ASSERT_FLOAT_EQ(v, static_cast<float>(sony.angles_deg()[c]))
                    << demosaic_method_name(method);
        }
    }
}

TEST(MicrogridDemosaic, LinearFieldIsExactForBilinearAndNewtonButNotForSuperPixel) {
    // S0, S1, S2 linear in x and y: bilinear interpolation and the symmetric Newton stencil are
    // exact away from the mirrored border; a super-pixel's four analyzers see four places, so its
    // S1/S2 are biased by the gradient (the IFOV error, Ratliff et al. 2009).
    const StokesScene scene = testing::integrate_scene(32, 32, [](double x, double y) {
        return testing::StokesPoint{100.0 + 2.0 * x + 1.0 * y, 10.0 + 0.6 * x - 0.3 * y,
                                    -5.0 + 0.2 * x + 0.5 * y};
    });
    const StokesErrors bilinear = measure(scene, DemosaicMethod::Bilinear, false);
    const StokesErrors newton = measure(scene, DemosaicMethod::Newton, false);
    const StokesErrors super_pixel = measure(scene, DemosaicMethod::SuperPixel, false);
    EXPECT_LT(std::max({bilinear.s0_rms, bilinear.s1_rms, bilinear.s2_rms}), 1e-3);
    EXPECT_LT(std::max({newton.s0_rms, newton.s1_rms, newton.s2_rms}), 1e-3);
    EXPECT_GT(super_pixel.s1_rms, 0.5);
}

TEST(MicrogridDemosaic, InterpolationBeatsSuperPixelOnASmoothField) {
    const StokesScene scene = testing::smooth_scene(96, 96);
    const StokesErrors super_pixel = measure(scene, DemosaicMethod::SuperPixel, false);
    for (DemosaicMethod method : {DemosaicMethod::Bilinear, DemosaicMethod::Newton}) {
        const StokesErrors e = measure(scene, method, false);
        EXPECT_LT(e.s1_rms, 0.5 * super_pixel.s1_rms) << demosaic_method_name(method);
        EXPECT_LT(e.s2_rms, 0.5 * super_pixel.s2_rms) << demosaic_method_name(method);
        EXPECT_LT(e.dolp_rms, 0.5 * super_pixel.dolp_rms) << demosaic_method_name(method);
    }
}

TEST(MicrogridDemosaic, NewtonBeatsBilinearWhereTheAnalyzersShareTheIntensityTexture) {
    // The Newton stencil borrows the own analyzer's curvature for the others (⅛·Laplacian): it
    // gains where the scene's texture is in intensity, common to all four analyzers (here
    // unpolarized). Where polarization itself is textured as strongly as intensity it does not (see
    // the table).
    const StokesScene scene = testing::smooth_scene(96, 96, true);
    const StokesErrors bilinear = measure(scene, DemosaicMethod::Bilinear, false);
    const StokesErrors newton = measure(scene, DemosaicMethod::Newton, false);
    EXPECT_LT(newton.s0_rms, 0.8 * bilinear.s0_rms);
    EXPECT_LT(newton.dolp_rms, 0.8 * bilinear.dolp_rms);
}

TEST(MicrogridDemosaic, NewtonHalvesTheFalseDolpOfBilinearAtAnUnpolarizedEdge) {
    // The truth is unpolarized everywhere, so any DoLP is the IFOV artefact. Vertical, off-grid and
    // slanted edges; only pixels within 3 px of the edge are compared.
    for (const auto& [x0, slope] : {std::pair{48.0, 0.0}, std::pair{48.37, 0.0},
                                    std::pair{48.0, 0.35}, std::pair{48.0, 1.0}}) {
        const StokesScene scene = testing::unpolarized_edge_scene(96, 96, x0, slope);
        const StokesErrors bilinear = measure(scene, DemosaicMethod::Bilinear, true);
        const StokesErrors newton = measure(scene, DemosaicMethod::Newton, true);
        EXPECT_GT(bilinear.dolp_rms, 0.05) << "x0 " << x0 << " slope " << slope;
        EXPECT_LT(newton.dolp_rms, 0.5 * bilinear.dolp_rms) << "x0 " << x0 << " slope " << slope;
    }
}

TEST(MicrogridDemosaic, RefusesFramesItCannotDemosaic) {
    const MicrogridPattern sony = MicrogridPattern::sony_imx250mzr();
    std::vector<float> frame(6 * 4, 1.0f);
    auto message = [&](int w, int h) {
        try {
            demosaic_microgrid(frame, w, h, sony, DemosaicMethod::Newton, "cam.png");
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message(5, 4).find("cam.png: 5×4 pixels"), std::string::npos) << message(5, 4);
    EXPECT_NE(message(2, 12).find("at least 4"), std::string::npos);
    EXPECT_NE(message(8, 4).find("24 values for a 8×4 frame"), std::string::npos) << message(8, 4);
    frame[7] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NE(message(6, 4).find("pixel (x=1, y=1)"), std::string::npos) << message(6, 4);
    EXPECT_THROW(parse_demosaic_method("cubic"), Error);
    EXPECT_EQ(parse_demosaic_method("newton"), DemosaicMethod::Newton);
}

TEST(MicrogridStokes, SonyLayoutLightPolarizedAlongRowsGivesPositiveS1AndZeroAoP) {
    // Written by hand, not by the forward model: light fully polarized along the image rows (0°)
    // reads 1 behind the 0° analyzers (cell (1,1) of the Sony layout), 0 behind 90° ((0,0)) and ½
    // behind 45° and 135° (Malus). ARCHITECTURE.md: S1 = I0 − I90 = 1, S2 = I45 − I135 = 0, AoP =
    // 0°.
    const int w = 8, h = 8;
    std::vector<float> mosaic(static_cast<std::size_t>(w * h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const int cell = (y & 1) * 2 + (x & 1);
            mosaic[static_cast<std::size_t>(y * w + x)] = cell == 3   ? 1.0f
                                                          : cell == 0 ? 0.0f
                                                                      : 0.5f;
        }
    for (DemosaicMethod method : kMethods) {
        MicrogridReductionOptions options;
        options.method = method;
        const Image stokes =
            reduce_microgrid(mosaic, w, h, MicrogridPattern::sony_imx250mzr(), options);
        EXPECT_NEAR(stokes.at("S0", 2, 2), 1.0f, 1e-6) << demosaic_method_name(method);
        EXPECT_NEAR(stokes.at("S1", 2, 2), 1.0f, 1e-6) << demosaic_method_name(method);
        EXPECT_NEAR(stokes.at("S2", 2, 2), 0.0f, 1e-6) << demosaic_method_name(method);
        EXPECT_NEAR(stokes.at("DoLP", 2, 2), 1.0f, 1e-6) << demosaic_method_name(method);
        const float aop_deg = stokes.at("AoP", 2, 2);  // [0°, 180°): 0° may come out as 180° − tiny
        EXPECT_LT(std::min(aop_deg, 180.0f - aop_deg), 1e-4f) << demosaic_method_name(method);
    }
}

TEST(MicrogridStokes, RecordsPatternAndMethodAndChecksTheAnalyzerModel) {
    const MicrogridPattern sony = MicrogridPattern::sony_imx250mzr();
    const std::vector<float> mosaic(8 * 8, 10.0f);
    MicrogridReductionOptions options;
    options.method = DemosaicMethod::SuperPixel;
    const Image stokes = reduce_microgrid(mosaic, 8, 8, sony, options);
    EXPECT_EQ(stokes.width(), 4);
    EXPECT_EQ(std::get<std::string>(stokes.attributes().at("demosaic_method")), "super-pixel");
    EXPECT_EQ(MicrogridPattern::from_attributes(stokes.attributes()).text(), "90,45,135,0");
    EXPECT_NEAR(stokes.at("S0", 1, 1), 20.0f, 1e-5);  // four analyzers each seeing ½·S0
    options.analyzer = AnalyzerModel::ideal({0.0, 45.0, 90.0, 120.0});
    EXPECT_THROW(reduce_microgrid(mosaic, 8, 8, sony, options), Error);
    options.analyzer = AnalyzerModel::non_ideal({0.0, 45.0, 90.0, 135.0}, 50.0, 0.0);
    EXPECT_NO_THROW(reduce_microgrid(mosaic, 8, 8, sony, options));
}

/// A uniform unpolarized field S0 = 100 measured with independent Gaussian noise of σ = 1 per
/// pixel: every Stokes error is noise, so this shows each method's noise gain.
StokesErrors measure_noisy_flat(DemosaicMethod method) {
    const StokesScene scene = testing::integrate_scene(128, 128, [](double, double) {
        return testing::StokesPoint{100.0, 0.0, 0.0};
    });
    std::vector<float> mosaic =
        microgrid_from_stokes(scene.s0, scene.s1, scene.s2, scene.width, scene.height,
                              MicrogridPattern::sony_imx250mzr());
    std::mt19937 rng(9);
    std::normal_distribution<float> noise(0.0f, 1.0f);
    for (float& v : mosaic) v += noise(rng);
    MicrogridReductionOptions options;
    options.method = method;
    options.reduction.project_to_realizable = false;
    const Image stokes = reduce_microgrid(mosaic, scene.width, scene.height,
                                          MicrogridPattern::sony_imx250mzr(), options);
    return compare_to_truth(stokes, scene.s0, scene.s1, scene.s2, scene.width, scene.height, 4);
}

TEST(MicrogridDemosaic, NoiseGainOfEachMethodIsBounded) {
    // Ideal analyzers at 0/45/90/135° give σ(S1) = σ(S2) = √2·σ and σ(S0) = σ for one super-pixel
    // of independent σ noise (S0 = ½ΣI, S1 = I0 − I90). Interpolation averages neighbours, so it
    // may only lower that, not raise it; the edge-directed weighting may not raise it above
    // super-pixel either.
    const StokesErrors super_pixel = measure_noisy_flat(DemosaicMethod::SuperPixel);
    EXPECT_NEAR(super_pixel.s1_rms, std::sqrt(2.0), 0.1);
    EXPECT_NEAR(super_pixel.s0_rms, 1.0, 0.1);
    for (DemosaicMethod method : {DemosaicMethod::Bilinear, DemosaicMethod::Newton}) {
        const StokesErrors e = measure_noisy_flat(method);
        EXPECT_LT(e.s1_rms, super_pixel.s1_rms * 1.05) << demosaic_method_name(method);
        EXPECT_LT(e.s2_rms, super_pixel.s2_rms * 1.05) << demosaic_method_name(method);
    }
}

TEST(MicrogridAccuracy, TablePerMethod) {
    // Prints the table of docs/microgrid.md; asserts only what the other tests pin.
    struct Case {
        const char* name;
        StokesScene scene;
        bool edge_only;
    };
    const Case cases[] = {
        {"smooth field, intensity texture only", testing::smooth_scene(128, 128, true), false},
        {"smooth field, polarization texture", testing::smooth_scene(128, 128), false},
        {"unpolarized edge, vertical", testing::unpolarized_edge_scene(128, 128, 64.37, 0.0), true},
        {"unpolarized edge, slope 0.35", testing::unpolarized_edge_scene(128, 128, 64.0, 0.35),
         true},
        {"polarized edge, slope 0.35", testing::polarized_edge_scene(128, 128, 64.0, 0.35), true},
    };
    std::printf(
        "| scene | method | S0 RMS | S1 RMS | S2 RMS | DoLP RMS error | DoLP max error "
        "|\n|---|---|---|---|---|---|---|\n");
    for (const Case& c : cases)
        for (DemosaicMethod method : kMethods) {
            const StokesErrors e = measure(c.scene, method, c.edge_only);
            std::printf("| %s | %s | %.3f | %.3f | %.3f | %.4f | %.4f |\n", c.name,
                        std::string(demosaic_method_name(method)).c_str(), e.s0_rms, e.s1_rms,
                        e.s2_rms, e.dolp_rms, e.dolp_max);
            EXPECT_GT(e.pixels, 0u);
        }
    for (DemosaicMethod method : kMethods) {
        const StokesErrors e = measure_noisy_flat(method);
        std::printf(
            "| flat unpolarized S0 = 100, noise σ = 1 | %s | %.3f | %.3f | %.3f | %.4f | %.4f |\n",
            std::string(demosaic_method_name(method)).c_str(), e.s0_rms, e.s1_rms, e.s2_rms,
            e.dolp_rms, e.dolp_max);
    }
}

}  // namespace
}  // namespace tirpol::calibration
