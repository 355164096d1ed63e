// Polarimetric calibration and Stokes reduction: the DRM against the paper's eqs 14–16, the
// analyzer model estimated from a known polarized source, the wire-grid τ/B model, propagated
// uncertainties against a Monte-Carlo spread, and the image Stokes convention of ARCHITECTURE.md.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <random>

#include "tirpol/calibration/analyzer.h"
#include "tirpol/calibration/stokes_reduction.h"
#include "tirpol/core/error.h"
#include "tirpol/core/geometry.h"
#include "tirpol/core/interrupt_signals.h"
#include "tirpol/core/radiometry.h"
#include "tirpol/core/stokes.h"

namespace tirpol::calibration {
namespace {

const std::vector<double> kAngles{0.0, 45.0, 90.0, 135.0};

TEST(Analyzer, IdealDrmIsPaperEquations14To16) {
    // Gartley et al. eqs 14–16: S0 = ½ΣL(α), S1 = L(0) − L(90), S2 = L(45) − L(135).
    const Eigen::Matrix3Xd drm = AnalyzerModel::ideal(kAngles).data_reduction_matrix();
    Eigen::Matrix<double, 3, 4> paper;
    paper << 0.5, 0.5, 0.5, 0.5, 1.0, 0.0, -1.0, 0.0, 0.0, 1.0, 0.0, -1.0;
    EXPECT_LT((drm - paper).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Analyzer, RowsAreTheTopRowOfCoreMuellerPolarizerForAnyAngleSet) {
    // The analyzer row must agree with core's Mueller matrices (same frame convention), and W⁺W = I
    // for N = 3, 5, 6 angles (Tyo et al. 2006).
    for (const std::vector<double>& angles :
         {std::vector<double>{0, 60, 120}, std::vector<double>{0, 36, 72, 108, 144},
          std::vector<double>{10, 40, 70, 100, 130, 160}}) {
        const auto model = AnalyzerModel::non_ideal(angles, 400.0, 1.5, 0.8);
        for (const auto& p : model.positions) {
            const MuellerMatrix m =
                polarizer_with_extinction(deg_to_rad(p.axis_angle_deg), 0.8, 400.0);
            const Eigen::RowVector3d expected = m.row(0).head<3>() / p.relative_transmission;
            EXPECT_LT((p.row() - expected).cwiseAbs().maxCoeff(), 1e-12);
        }
        const Eigen::Matrix3d identity = model.data_reduction_matrix() * model.measurement_matrix();
        EXPECT_LT((identity - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-10);
    }
}

TEST(Analyzer, TooFewOrDegenerateAnglesAreRejected) {
    EXPECT_THROW(AnalyzerModel::ideal({0.0, 90.0}).data_reduction_matrix(), Error);
    try {
        AnalyzerModel::ideal({0.0, 90.0, 180.0}).data_reduction_matrix();
        FAIL() << "0/90/180 cannot give S2";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), testing::HasSubstr("0°, 90°, 180°"));
    }
}

// Measurements of a known source through a non-ideal analyzer, computed with core's Mueller
// calculus.
std::vector<KnownSourceMeasurement> known_source_set(double extinction, double offset_deg,
                                                     double t_max, double background, double noise,
                                                     unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> unit(0.0, 1.0);
    std::vector<KnownSourceMeasurement> set;
    // A blackbody behind a reference polarizer at 0/45/90/135° (fully polarized), at two
    // temperatures.
    for (double l : {30.0, 45.0})
        for (double ref : kAngles) {
            KnownSourceMeasurement m;
            const StokesVector s = linear_polarizer(deg_to_rad(ref)) * unpolarized(l);
            m.source_stokes = s.head<3>();
            for (double a : kAngles) {
                const MuellerMatrix an =
                    polarizer_with_extinction(deg_to_rad(a + offset_deg), t_max, extinction);
                m.intensities.push_back((an * s)[0] + background + noise * unit(rng));
            }
            set.push_back(m);
        }
    return set;
}

TEST(Analyzer, LeastSquaresRecoversExtinctionRatioAngleOffsetAndTransmission) {
    const auto set = known_source_set(50.0, 2.5, 0.8, 3.0, 0.0, 1);
    const AnalyzerModel model = estimate_analyzer(kAngles, set);
    for (const auto& p : model.positions) {
        EXPECT_NEAR(p.axis_angle_deg - p.nominal_angle_deg, 2.5, 1e-9);
        EXPECT_NEAR(p.extinction_ratio(), 50.0, 1e-6);
        EXPECT_NEAR(p.relative_transmission, 0.8 + 0.8 / 50.0, 1e-12);
        EXPECT_NEAR(p.background, 3.0, 1e-9);
    }
    // With noise (σ = 0.02 on signals of ~10), the angle offset stays within 0.1°.
    const AnalyzerModel noisy =
        estimate_analyzer(kAngles, known_source_set(50.0, 2.5, 0.8, 3.0, 0.02, 2));
    for (const auto& p : noisy.positions)
        EXPECT_NEAR(p.axis_angle_deg - p.nominal_angle_deg, 2.5, 0.1);
}

TEST(Analyzer, SourcesThatDoNotSpanTheModelAreRejected) {
    auto set = known_source_set(50.0, 0.0, 0.8, 0.0, 0.0, 3);
    set.resize(4);  // one intensity only: S0 and the offset cannot be separated
    try {
        estimate_analyzer(kAngles, set);
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), testing::HasSubstr("two source intensities"));
    }
}

TEST(StokesReduction, ImageConventionFollowsArchitecture) {
    // Light polarized along the image rows (core's polarizer at 0°) gives S1 > 0 and AoP 0°; along
    // the image's vertical (90°, to the top) S1 < 0; at +45° (counter-clockwise) S2 > 0, AoP 45°.
    const auto model = AnalyzerModel::ideal(kAngles);
    struct Case {
        double pol_deg, s1_sign, s2_sign, aop;
    };
    for (const Case c :
         {Case{0, 1, 0, 0}, Case{90, -1, 0, 90}, Case{45, 0, 1, 45}, Case{135, 0, -1, 135}}) {
        const StokesVector scene = linear_polarizer(deg_to_rad(c.pol_deg)) * unpolarized(10.0);
        std::vector<AnalyzerImage> images;
        for (double a : kAngles) {
            const double i = (linear_polarizer(deg_to_rad(a)) * scene)[0];
            images.push_back({a, {static_cast<float>(i)}, {}, "synthetic"});
        }
        const Image s = reduce_stokes(images, 1, 1, model);
        EXPECT_NEAR(s.channel("S0")[0], scene[0], 1e-5);
        EXPECT_NEAR(s.channel("S1")[0], c.s1_sign * scene[0], 1e-5);
        EXPECT_NEAR(s.channel("S2")[0], c.s2_sign * scene[0], 1e-5);
        EXPECT_NEAR(std::fmod(s.channel("AoP")[0] + 1.0, 180.0) - 1.0, c.aop, 1e-3);
        EXPECT_NEAR(s.channel("DoLP")[0], 1.0, 1e-5);
    }
}

TEST(StokesReduction, PropagatedUncertaintyMatchesMonteCarloSpreadAndOutputIsRealizable) {
    // 64×64 independent pixels looking at the same weakly polarized scene through a 400:1 grid; the
    // spread of S1 over pixels must match the propagated S1_std (σ of a σ-estimate from 4096
    // samples ≈ 1.1 %, tolerance 5 %).
    constexpr int kW = 64, kH = 64;
    const auto model = AnalyzerModel::non_ideal(kAngles, 400.0, 0.0, 0.8);
    const StokesVector scene = linearly_polarized(40.0, 0.05, deg_to_rad(30.0));
    std::mt19937 rng(4);
    const double sigma = 0.2;
    std::normal_distribution<double> noise(0.0, sigma);
    std::vector<AnalyzerImage> images;
    for (const auto& p : model.positions) {
        AnalyzerImage im{p.nominal_angle_deg, {}, {}, "synthetic"};
        const double truth = p.relative_transmission * p.row().dot(scene.head<3>());
        for (int i = 0; i < kW * kH; ++i) {
            im.signal.push_back(static_cast<float>(truth + noise(rng)));
            im.signal_std.push_back(static_cast<float>(sigma));
        }
        images.push_back(im);
    }
    const Image s = reduce_stokes(images, kW, kH, model);
    for (const char* c : {"S0", "S1", "S2"}) {
        const auto& v = s.channel(c);
        double mean = 0.0, var = 0.0;
        for (float x : v) mean += x;
        mean /= static_cast<double>(v.size());
        for (float x : v) var += (x - mean) * (x - mean);
        const double spread = std::sqrt(var / static_cast<double>(v.size() - 1));
        const double predicted = s.channel(std::string(c) + "_std")[0];
        EXPECT_NEAR(spread / predicted, 1.0, 0.05) << c;
    }
    EXPECT_NEAR(s.channel("S1")[100], scene[1], 6 * s.channel("S1_std")[100]);
    for (std::size_t i = 0; i < s.pixel_count(); ++i) {
        const StokesVector v{s.channel("S0")[i], s.channel("S1")[i], s.channel("S2")[i], 0.0};
        ASSERT_TRUE(is_realizable(v, 1e-6)) << "pixel " << i;
    }
}

TEST(StokesReduction, UncertaintyIncludesTheWireGridFitErrorWhichDoesNotAverageAway) {
    // τ and B are fitted per pixel from blackbody frames that are themselves noisy; that error is
    // the same in every frame of a session, so a scene averaged over many frames keeps it. 64×64
    // pixels, each an independent realisation: blackbody means at 278/308 K with σ_bb, scene means
    // with σ_s. The spread of S − truth over pixels must match the reported S_std (σ of a
    // σ-estimate from 4096 samples ≈ 1.1 %, tolerance 5 %); with the grid's error left out it reads
    // ≥ 10 % low here.
    constexpr int kW = 64, kH = 64, kN = kW * kH;
    const Band band(8.0, 14.0);
    const auto model = AnalyzerModel::ideal(kAngles);
    const double tau = 0.7, background = 3.0, sigma_bb = 0.03, sigma_scene = 0.03;
    const StokesVector scene = linearly_polarized(band.radiance(285.0), 0.05, deg_to_rad(30.0));
    std::mt19937 rng(11);
    std::normal_distribution<double> unit(0.0, 1.0);
    std::vector<PolarizedBlackbodyFrame> frames;
    for (double a : kAngles)
        for (double t : {278.15, 308.15}) {
            PolarizedBlackbodyFrame f{a, t, {}, fmt::format("bb {:g} K at {:g}°", t, a), {}};
            for (int i = 0; i < kN; ++i) {
                f.signal.push_back(static_cast<float>(tau * 0.5 * band.radiance(t) + background +
                                                      sigma_bb * unit(rng)));
                f.signal_std.push_back(static_cast<float>(sigma_bb));
            }
            frames.push_back(std::move(f));
        }
    const WireGridCalibration grid = fit_wire_grid(frames, kW, kH, band);
    WireGridCalibration grid_without_covariance = grid;
    for (auto& p : grid_without_covariance.positions) p.tau_var.clear();
    std::vector<AnalyzerImage> images;
    for (const auto& p : model.positions) {
        AnalyzerImage im{p.nominal_angle_deg, {}, {}, "scene"};
        const double truth = tau * p.row().dot(scene.head<3>()) + background;
        for (int i = 0; i < kN; ++i) {
            im.signal.push_back(static_cast<float>(truth + sigma_scene * unit(rng)));
            im.signal_std.push_back(static_cast<float>(sigma_scene));
        }
        images.push_back(std::move(im));
    }
    const Image s = reduce_stokes(images, kW, kH, model, &grid);
    const Image temporal_only = reduce_stokes(images, kW, kH, model, &grid_without_covariance);
    EXPECT_EQ(std::get<std::string>(s.attributes().at("std_includes")),
              "temporal noise and the wire-grid calibration's fit error");
    for (int q = 0; q < 3; ++q) {
        const std::string c = fmt::format("S{}", q);
        double spread = 0.0;
        for (float x : s.channel(c)) spread += (x - scene[q]) * (x - scene[q]);
        spread = std::sqrt(spread / kN);
        EXPECT_NEAR(spread / s.channel(c + "_std")[0], 1.0, 0.05) << c;
        EXPECT_GT(spread / temporal_only.channel(c + "_std")[0], 1.10) << c;
    }
}

TEST(StokesReduction, NoisyUnrealizablePixelsAreProjectedOntoTheConeAndCounted) {
    // Noise comparable to the signal: many pixels come out with √(S1²+S2²) > S0 from eqs 14–16.
    constexpr int kN = 1000;
    std::mt19937 rng(8);
    std::normal_distribution<double> noise(0.0, 0.5);
    std::vector<AnalyzerImage> images;
    for (double a : kAngles) {
        AnalyzerImage im{a, {}, {}, "noisy"};
        for (int i = 0; i < kN; ++i) im.signal.push_back(static_cast<float>(0.5 + noise(rng)));
        images.push_back(im);
    }
    const auto model = AnalyzerModel::ideal(kAngles);
    ReductionOptions raw;
    raw.project_to_realizable = false;
    const Image as_measured = reduce_stokes(images, kN, 1, model, nullptr, raw);
    const Image projected = reduce_stokes(images, kN, 1, model);
    const int count = stokes_reduction_record(projected).unrealizable_pixels;
    EXPECT_GT(count, 50);
    int unrealizable_left = 0, unrealizable_before = 0;
    for (std::size_t i = 0; i < kN; ++i) {
        const StokesVector p{projected.channel("S0")[i], projected.channel("S1")[i],
                             projected.channel("S2")[i], 0.0};
        const StokesVector m{as_measured.channel("S0")[i], as_measured.channel("S1")[i],
                             as_measured.channel("S2")[i], 0.0};
        if (p[0] >= 0.0 && !is_realizable(p, 1e-6)) ++unrealizable_left;
        if (m[0] >= 0.0 && !is_realizable(m, 1e-6)) ++unrealizable_before;
        EXPECT_DOUBLE_EQ(p[0], m[0]);  // S0 is kept, (S1, S2) scaled
    }
    EXPECT_EQ(unrealizable_left, 0);
    EXPECT_EQ(unrealizable_before, count);
}

TEST(StokesReduction,
     TheRecordOfAnImageNotMadeByAReductionIsAnErrorNamingTheAttributeAndAnUnstatedGridIsEmpty) {
    const auto model = AnalyzerModel::ideal(kAngles);
    std::vector<AnalyzerImage> images;
    for (double a : kAngles) images.push_back({a, {1.0f, 2.0f}, {}, "flat"});
    Image stokes = reduce_stokes(images, 2, 1, model);
    EXPECT_EQ(stokes_reduction_record(stokes).unrealizable_pixels, 0);
    EXPECT_EQ(stokes_reduction_record(stokes).wire_grid_corrected, std::optional<bool>(false));
    stokes.attributes()[kWireGridCorrectedAttribute] = std::string("yes");
    EXPECT_THAT([&] { stokes_reduction_record(stokes); },
                testing::ThrowsMessage<Error>(testing::HasSubstr("'wire_grid_corrected' is not")));
    // An image that does not say whether a wire grid was removed is read, and says so.
    stokes.attributes().erase(kWireGridCorrectedAttribute);
    EXPECT_EQ(stokes_reduction_record(stokes).wire_grid_corrected, std::nullopt);
    stokes.attributes().erase(kUnrealizablePixelsAttribute);
    EXPECT_THAT([&] { stokes_reduction_record(stokes); },
                testing::ThrowsMessage<Error>(testing::HasSubstr("no attribute 'unrealizable")));
}

TEST(StokesReduction, ASetCancelFlagStopsTheReductionAndAnUnsetOneChangesNothing) {
    // The flag Ctrl-C sets from Python (python/src/interruptible.h): checked at each row start.
    constexpr int kW = 8, kH = 4;
    const auto model = AnalyzerModel::ideal(kAngles);
    std::vector<AnalyzerImage> images;
    for (const auto& p : model.positions)
        images.push_back(
            {p.nominal_angle_deg, std::vector<float>(kW * kH, 10.0f), {}, "synthetic"});
    std::atomic<bool> cancel{false};
    ReductionOptions options;
    options.cancel = &cancel;
    const Image unflagged = reduce_stokes(images, kW, kH, model, nullptr, options);
    EXPECT_EQ(unflagged.channel("S0"), reduce_stokes(images, kW, kH, model).channel("S0"));
    cancel = true;
    EXPECT_THROW(reduce_stokes(images, kW, kH, model, nullptr, options), Cancelled);
}

TEST(StokesReduction, BadInputsGiveClearErrorsAndNoOutput) {
    const auto model = AnalyzerModel::ideal(kAngles);
    auto make = [](double a, std::size_t n) {
        return AnalyzerImage{a, std::vector<float>(n, 1.0f), {}, fmt::format("frame {:g}", a)};
    };
    std::vector<AnalyzerImage> missing{make(0, 4), make(45, 4), make(90, 4)};
    try {
        reduce_stokes(missing, 2, 2, model);
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), testing::HasSubstr("no image at analyzer angle 135°"));
    }
    std::vector<AnalyzerImage> sizes{make(0, 4), make(45, 4), make(90, 4), make(135, 6)};
    EXPECT_THROW(reduce_stokes(sizes, 2, 2, model), Error);
    std::vector<AnalyzerImage> nan{make(0, 4), make(45, 4), make(90, 4), make(135, 4)};
    nan[2].signal[3] = std::nanf("");
    try {
        reduce_stokes(nan, 2, 2, model);
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), testing::HasSubstr("frame 90"));
    }
}

TEST(WireGrid, BlackbodiesThroughThePolarizerRemoveGhostSkyReflectionAndGridEmission) {
    // Truth: per-pixel transmission (vignetting), a structured ghost of the camera interior, the
    // cold sky reflected by the tilted grid (different per angle: the grid reflects the
    // polarization it does not pass), the grid's own emission, and a 50:1 grid with a 2° mount
    // offset.
    constexpr int kW = 40, kH = 30;
    const Band band(8.0, 14.0);
    const auto truth_model = AnalyzerModel::non_ideal(kAngles, 50.0, 2.0, 0.8);
    auto tau = [&](int x, int y, std::size_t k) {
        const double r2 = std::pow((x - kW / 2.0) / kW, 2) + std::pow((y - kH / 2.0) / kH, 2);
        return truth_model.positions[k].relative_transmission * (1.0 - 0.3 * r2);
    };
    auto background = [&](int x, int y, std::size_t k) {
        const double ghost =
            2.0 * std::exp(-(std::pow(x - 12.0, 2) + std::pow(y - 10.0, 2)) / 30.0);
        const double sky =
            0.15 * band.radiance(230.0) * (1.0 + 0.5 * std::cos(deg_to_rad(2.0 * kAngles[k])));
        const double emission = 0.05 * band.radiance(285.0);
        return ghost + sky + emission;
    };
    auto observe = [&](int x, int y, std::size_t k, const StokesVector& s) {
        return tau(x, y, k) * truth_model.positions[k].row().dot(s.head<3>()) + background(x, y, k);
    };
    std::vector<PolarizedBlackbodyFrame> frames;
    for (std::size_t k = 0; k < kAngles.size(); ++k)
        for (double t : {278.15, 308.15}) {
            PolarizedBlackbodyFrame f{
                kAngles[k], t, {}, fmt::format("bb {:g} K at {:g}°", t, kAngles[k])};
            for (int y = 0; y < kH; ++y)
                for (int x = 0; x < kW; ++x)
                    f.signal.push_back(
                        static_cast<float>(observe(x, y, k, unpolarized(band.radiance(t)))));
            frames.push_back(f);
        }
    const WireGridCalibration grid = fit_wire_grid(frames, kW, kH, band);
    EXPECT_NEAR(grid.at(45.0).tau[static_cast<std::size_t>(3 * kW + 5)], tau(5, 3, 1), 1e-4);
    EXPECT_NEAR(grid.at(90.0).background[static_cast<std::size_t>(10 * kW + 12)],
                background(12, 10, 2), 1e-3);

    // Analyzer model from the known source (taken through the same grid: fitted on L_SLAR, τ and B
    // removed, so only the analyzer's row shape is estimated).
    const AnalyzerModel model =
        estimate_analyzer(kAngles, known_source_set(50.0, 2.0, 0.8, 0.0, 0.0, 5));

    // Scene: a panel with DoLP 4 % at AoP 90° (emission-dominated, vertical) at 290 K.
    const StokesVector scene = linearly_polarized(band.radiance(290.0), 0.04, deg_to_rad(90.0));
    std::vector<AnalyzerImage> images;
    for (std::size_t k = 0; k < kAngles.size(); ++k) {
        AnalyzerImage im{kAngles[k], {}, {}, "scene"};
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                im.signal.push_back(static_cast<float>(observe(x, y, k, scene)));
        images.push_back(im);
    }
    const Image s = reduce_stokes(images, kW, kH, model, &grid);
    const Image naive = reduce_stokes(images, kW, kH, AnalyzerModel::ideal(kAngles));
    double worst = 0.0, worst_naive = 0.0;
    for (std::size_t i = 0; i < s.pixel_count(); ++i) {
        worst = std::max(worst, std::abs(s.channel("S1")[i] - scene[1]));
        worst_naive = std::max(worst_naive, std::abs(naive.channel("S1")[i] - scene[1]));
        ASSERT_NEAR(s.channel("S0")[i], scene[0], 1e-3 * scene[0]);
    }
    EXPECT_LT(worst, 0.01 * std::abs(scene[1]));  // 1 % of the polarized signal
    EXPECT_GT(worst_naive, 0.5 * std::abs(scene[1]));

    // The wire-grid-corrected radiance per angle is the analyzer row applied to the scene.
    ReductionOptions with_slar;
    with_slar.include_slar = true;
    const Image slar = reduce_stokes(images, kW, kH, model, &grid, with_slar);
    const double expected = truth_model.positions[1].row().dot(scene.head<3>());
    EXPECT_NEAR(slar.at("L_SLAR_45", 7, 21), expected, 1e-3 * expected);
    EXPECT_FALSE(s.has_channel("L_SLAR_45"));
}

TEST(WireGrid, OneTemperaturePerAngleIsRejected) {
    std::vector<PolarizedBlackbodyFrame> frames{{0.0, 300.0, {1.0f}, "a"},
                                                {0.0, 300.0, {1.0f}, "b"}};
    try {
        fit_wire_grid(frames, 1, 1, Band(8.0, 14.0));
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), testing::HasSubstr("1 distinct temperature"));
    }
}

TEST(WireGrid, BackgroundFromSkyRadianceAndGridEmission) {
    const Band band(8.0, 14.0);
    // Isothermal check: a grid reflecting a sky at its own temperature with r + ε = 1 adds the
    // blackbody radiance of that temperature (Kirchhoff).
    EXPECT_NEAR(wire_grid_background(0.3, band.radiance(280.0), 0.7, 280.0, band),
                band.radiance(280.0), 1e-9);
    EXPECT_THROW(wire_grid_background(0.6, 10.0, 0.6, 280.0, band), Error);
}

}  // namespace
}  // namespace tirpol::calibration
