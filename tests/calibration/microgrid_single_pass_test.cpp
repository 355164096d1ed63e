// The single-pass microgrid reduction (demosaicing and Stokes in one pass over the rows, with the
// analyzer model's fixed 3×4 matrix) against the two-step path it replaces (demosaic_microgrid,
// then the general per-pixel reduce_stokes in double): equal to float rounding on random frames
// and on a smooth polarized scene, for every method, with ideal and non-ideal analyzers, and with
// the same attributes.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

#include "stokes_row.h"
#include "tirpol/calibration/microgrid_stokes.h"
#include "tirpol/calibration/stokes_reduction.h"
#include "tirpol/core/error.h"

namespace tirpol::calibration {
namespace {

constexpr DemosaicMethod kMethods[] = {DemosaicMethod::SuperPixel, DemosaicMethod::Bilinear,
                                       DemosaicMethod::Newton};

/// Independent uniform counts per pixel: every pixel a different "polarization", many of them
/// unrealizable after demosaicing, so the projection is exercised too.
std::vector<float> random_frame(int width, int height, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> counts(1000, 60000);
    std::vector<float> frame(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    for (float& v : frame) v = static_cast<float>(counts(rng));
    return frame;
}

/// A smooth partially polarized scene in 16-bit-like counts with noise, integer-valued.
std::vector<float> scene_frame(int width, int height, unsigned seed) {
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    std::vector<float> s0(n), s1(n), s2(n);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y * width + x);
            const double intensity = 24000.0 + 6000.0 * std::sin(x / 7.0) * std::cos(y / 5.0);
            const double dolp = 0.2 + 0.15 * std::sin((x + y) / 11.0);
            const double aop = (30.0 + 60.0 * std::sin(x / 13.0)) * std::numbers::pi / 180.0;
            s0[i] = static_cast<float>(intensity);
            s1[i] = static_cast<float>(intensity * dolp * std::cos(2.0 * aop));
            s2[i] = static_cast<float>(intensity * dolp * std::sin(2.0 * aop));
        }
    std::vector<float> frame =
        microgrid_from_stokes(s0, s1, s2, width, height, MicrogridPattern::sony_imx250mzr());
    std::mt19937 rng(seed);
    std::normal_distribution<float> noise(0.0f, 30.0f);
    for (float& v : frame) v = std::round(v + noise(rng));
    return frame;
}

double max_abs(const std::vector<float>& plane) {
    double m = 0.0;
    for (float v : plane) m = std::max(m, std::abs(static_cast<double>(v)));
    return m;
}

/// S0, S1, S2 within a few float ulps of the frame's largest S0; DoLP to the same relative
/// rounding; AoP where the polarized part is above 1 % of S0, to the angle that rounding error
/// subtends; the unrealizable count to the pixels whose DoLP is 1 to rounding; all other attributes
/// equal.
void expect_equal_to_float_rounding(const Image& fast, const Image& general,
                                    const std::string& what) {
    ASSERT_EQ(fast.width(), general.width()) << what;
    ASSERT_EQ(fast.height(), general.height()) << what;
    ASSERT_EQ(fast.channel_names(), general.channel_names()) << what;
    const double scale = max_abs(general.channel("S0"));
    const double s_tolerance = 4e-7 * scale;
    std::size_t checked_aop = 0, near_cone = 0;
    for (std::size_t i = 0; i < general.pixel_count(); ++i) {
        const double s0 = general.channel("S0")[i], s1 = general.channel("S1")[i],
                     s2 = general.channel("S2")[i];
        for (const char* name : {"S0", "S1", "S2"})
            ASSERT_NEAR(fast.channel(name)[i], general.channel(name)[i], s_tolerance)
                << what << " " << name << " pixel " << i;
        const double pl = std::hypot(s1, s2);
        ASSERT_NEAR(fast.channel("DoLP")[i], general.channel("DoLP")[i],
                    4.0 * s_tolerance / s0 + 1e-6)
            << what << " DoLP pixel " << i;
        if (std::abs(pl - s0) < 4.0 * s_tolerance) ++near_cone;
        if (pl > 0.01 * s0) {
            double d = std::abs(fast.channel("AoP")[i] - general.channel("AoP")[i]);
            d = std::min(d, 180.0 - d);
            const double tolerance_deg = 0.5 * (4.0 * s_tolerance / pl) * 180.0 / std::numbers::pi;
            ASSERT_LE(d, tolerance_deg + 2e-4) << what << " AoP pixel " << i;
            ++checked_aop;
        }
    }
    EXPECT_GT(checked_aop, general.pixel_count() / 2) << what;
    for (const auto& [name, value] : general.attributes()) {
        ASSERT_TRUE(fast.attributes().contains(name)) << what << " attribute " << name;
        if (name == kUnrealizablePixelsAttribute)
            EXPECT_NEAR(stokes_reduction_record(fast).unrealizable_pixels,
                        stokes_reduction_record(general).unrealizable_pixels,
                        static_cast<double>(near_cone))
                << what;
        else
            EXPECT_EQ(fast.attributes().at(name), value) << what << " attribute " << name;
    }
    EXPECT_EQ(fast.attributes().size(), general.attributes().size()) << what;
}

void compare_paths(const std::vector<float>& frame, int width, int height,
                   MicrogridReductionOptions options, const std::string& what) {
    const MicrogridPattern sony = MicrogridPattern::sony_imx250mzr();
    for (DemosaicMethod method : kMethods) {
        options.method = method;
        options.single_pass = true;
        const Image fast = reduce_microgrid(frame, width, height, sony, options);
        options.single_pass = false;
        const Image general = reduce_microgrid(frame, width, height, sony, options);
        expect_equal_to_float_rounding(fast, general,
                                       what + " " + std::string(demosaic_method_name(method)));
    }
}

TEST(MicrogridSinglePass, EqualsDemosaicThenReduceStokesOnRandomFrames) {
    for (unsigned seed : {1u, 2u, 3u}) {
        MicrogridReductionOptions options;
        compare_paths(random_frame(38, 26, seed), 38, 26, options,
                      "random seed " + std::to_string(seed));
        options.reduction.project_to_realizable = false;
        compare_paths(random_frame(38, 26, seed), 38, 26, options,
                      "random, unprojected, seed " + std::to_string(seed));
    }
}

TEST(MicrogridSinglePass, EqualsDemosaicThenReduceStokesOnAPolarizedScene) {
    compare_paths(scene_frame(64, 48, 4), 64, 48, {}, "scene");
}

TEST(MicrogridSinglePass, EqualsTheGeneralPathWithANonIdealAnalyzerModel) {
    // Each micro-polarizer position its own axis error, diattenuation, transmission and background
    // (the calibrated reduction of a camera with one model for all pixels).
    MicrogridReductionOptions options;
    const double nominal[4] = {90.0, 45.0, 135.0, 0.0};
    const double axis_error_deg[4] = {1.5, -0.7, 0.4, -2.0};
    const double diattenuation[4] = {0.93, 0.97, 0.9, 0.95};
    const double transmission[4] = {0.88, 1.05, 0.97, 1.1};
    const double background[4] = {120.0, -40.0, 15.0, 300.0};
    for (std::size_t k = 0; k < 4; ++k)
        options.analyzer.positions.push_back({nominal[k], nominal[k] + axis_error_deg[k],
                                              diattenuation[k], transmission[k], background[k]});
    compare_paths(scene_frame(64, 48, 5), 64, 48, options, "non-ideal scene");
    compare_paths(random_frame(38, 26, 6), 38, 26, options, "non-ideal random");
}

TEST(MicrogridSinglePass, SixteenBitFramesGiveTheFloatResult) {
    const std::vector<float> frame = scene_frame(40, 30, 7);
    const std::vector<std::uint16_t> counts(frame.begin(), frame.end());
    const MicrogridPattern sony = MicrogridPattern::sony_imx250mzr();
    for (DemosaicMethod method : kMethods)
        for (bool single_pass : {true, false}) {
            MicrogridReductionOptions options;
            options.method = method;
            options.single_pass = single_pass;
            const Image from_float = reduce_microgrid(frame, 40, 30, sony, options);
            const Image from_counts =
                reduce_microgrid(std::span<const std::uint16_t>(counts), 40, 30, sony, options);
            for (const std::string& name : from_float.channel_names())
                EXPECT_EQ(from_counts.channel(name), from_float.channel(name))
                    << demosaic_method_name(method) << " " << name;
        }
    EXPECT_THROW(reduce_microgrid(std::span<const std::uint16_t>(counts).first(counts.size() - 1),
                                  40, 30, sony),
                 Error);
}

TEST(MicrogridSinglePass, RefusesANonFinitePixelNamingIt) {
    std::vector<float> frame = scene_frame(16, 12, 8);
    frame[5 * 16 + 3] = std::numeric_limits<float>::quiet_NaN();
    try {
        reduce_microgrid(frame, 16, 12, MicrogridPattern::sony_imx250mzr());
        FAIL() << "a NaN pixel was reduced";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("x=3, y=5"), std::string::npos) << e.what();
    }
}

TEST(MicrogridSinglePass, PolynomialAopMatchesAtan2ToFloatRounding) {
    // AoP = ½·atan2(S2, S1) in [0°, 180°) over every direction, including the axes and the
    // octant boundaries where the atan's range reduction switches.
    double worst = 0.0;
    for (int k = 0; k <= 72000; ++k) {
        const double angle = k * 2.0 * std::numbers::pi / 72000.0;
        for (double radius : {1e-3, 1.0, 3e4}) {
            const auto s1 = static_cast<float>(radius * std::cos(angle));
            const auto s2 = static_cast<float>(radius * std::sin(angle));
            double expected = 0.5 * std::atan2(static_cast<double>(s2), static_cast<double>(s1)) *
                              180.0 / std::numbers::pi;
            if (expected < 0.0) expected += 180.0;
            const double got = detail::aop_deg(s1, s2);
            ASSERT_GE(got, 0.0);
            ASSERT_LE(got, 180.0);
            double d = std::abs(got - expected);
            worst = std::max(worst, std::min(d, 180.0 - d));
        }
    }
    EXPECT_LT(worst, 2e-5);  // degrees: a few float ulps of 180°
    EXPECT_EQ(detail::aop_deg(0.0f, 0.0f), 0.0f);
    EXPECT_EQ(detail::aop_deg(-1.0f, 0.0f), 90.0f);
    EXPECT_EQ(detail::aop_deg(-1.0f, -0.0f), 90.0f);
    EXPECT_TRUE(std::isnan(detail::aop_deg(std::numeric_limits<float>::quiet_NaN(), 1.0f)));
}

TEST(MicrogridSinglePass, SlarOutputTakesTheGeneralPath) {
    MicrogridReductionOptions options;
    options.reduction.include_slar = true;
    const Image stokes = reduce_microgrid(scene_frame(16, 12, 9), 16, 12,
                                          MicrogridPattern::sony_imx250mzr(), options);
    EXPECT_TRUE(stokes.has_channel("L_SLAR_45"));
}

}  // namespace
}  // namespace tirpol::calibration
