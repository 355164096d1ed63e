// Calibration quality: residuals per set-point, the structured-residual warning
// of a linear fit to a curved response, NEDT against its hand-computed value, warnings when a
// calibration is applied beyond its blackbody or FPA range, and the one-page summary files.

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "synthetic_fpa_camera.h"
#include "test_support.h"
#include "tirpol/calibration/radiometric.h"
#include "tirpol/calibration/session_calibration.h"
#include "tirpol/calibration/synthetic_session.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/exr_io.h"

namespace tirpol::calibration {
namespace {

const Band kBand(8.0, 14.0);
const std::vector<double> kSetPointsK{283.15, 293.15, 303.15, 313.15, 323.15, 333.15};
constexpr int kW = 32, kH = 24;
constexpr double kNoise = 4.0;  // counts per frame
constexpr int kFrames = 16;

/// A camera with counts = 5000 + 100·L + q·L² per pixel (± 5 % gain) and white noise of the mean.
std::vector<BlackbodyFrame> curved_camera_frames(double q, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> unit(0.0, 1.0);
    std::vector<double> gain;
    for (int i = 0; i < kW * kH; ++i) gain.push_back(100.0 * (1.0 + 0.05 * unit(rng)));
    std::vector<BlackbodyFrame> frames;
    for (double t : kSetPointsK) {
        BlackbodyFrame f;
        f.temperature_k = t;
        f.frames = kFrames;
        f.source = fmt::format("bb {:.2f} K", t);
        const double l = kBand.radiance(t);
        for (int i = 0; i < kW * kH; ++i) {
            f.counts.push_back(static_cast<float>(5000.0 + gain[static_cast<std::size_t>(i)] * l +
                                                  q * l * l +
                                                  kNoise / std::sqrt(kFrames) * unit(rng)));
            f.counts_std.push_back(static_cast<float>(kNoise));
        }
        frames.push_back(std::move(f));
    }
    return frames;
}

TEST(CalibrationQuality, LinearFitOfACurvedResponseWarnsAndSuggestsQuadratic) {
    // q = 0.03 counts/(W/(m²·sr))² over 37–77 W/(m²·sr) bends the response by q·ΔL²/8 ≈ 6 counts ≈
    // 70 mK at mid-range: the mildly non-linear camera of the issue.
    const auto frames = curved_camera_frames(0.03, 1);
    const auto linear = fit_radiometric(frames, kW, kH, kBand);
    const auto q_linear = assess_calibration(linear, frames);
    ASSERT_EQ(q_linear.set_points.size(), kSetPointsK.size());
    ASSERT_EQ(q_linear.warnings.size(), 1u);
    EXPECT_THAT(q_linear.warnings[0], testing::HasSubstr("--quadratic"));
    // A convex response under a straight line: positive residuals at the ends, negative inside.
    EXPECT_GT(q_linear.set_points.front().mean_mk, kStructuredResidualMk);
    EXPECT_GT(q_linear.set_points.back().mean_mk, kStructuredResidualMk);
    EXPECT_LT(q_linear.set_points[2].mean_mk, -kStructuredResidualMk);

    RadiometricOptions quadratic;
    quadratic.quadratic = true;
    const auto curved = fit_radiometric(frames, kW, kH, kBand, quadratic);
    const auto q_curved = assess_calibration(curved, frames);
    EXPECT_TRUE(q_curved.warnings.empty());
    for (const auto& s : q_curved.set_points)
        EXPECT_LT(std::abs(s.mean_mk), 4.0 * s.standard_error_mk + 1.0);
}

TEST(CalibrationQuality, LinearCameraGivesNoWarningAndNoiseSizedResiduals) {
    const auto frames = curved_camera_frames(0.0, 2);
    const auto cal = fit_radiometric(frames, kW, kH, kBand);
    const auto q = assess_calibration(cal, frames);
    EXPECT_TRUE(q.warnings.empty());
    for (const auto& s : q.set_points) {
        // Residual of a 2-parameter fit to 6 points: σ_mean·√((6−2)/6) on average over the
        // set-points.
        const double sigma_mean_mk =
            kNoise / std::sqrt(kFrames) / (100.0 * kBand.radiance_dT(s.temperature_k)) * 1e3;
        EXPECT_LT(s.rms_mk, 1.5 * sigma_mean_mk);
        EXPECT_GT(s.rms_mk, 0.3 * sigma_mean_mk);
    }
}

TEST(CalibrationQuality, NedtMatchesHandComputedValue) {
    const auto frames = curved_camera_frames(0.0, 3);
    const auto q = assess_calibration(fit_radiometric(frames, kW, kH, kBand), frames);
    // Nearest set-point to 300 K is 303.15 K; NEDT = σ / (g·dL/dT) with median gain 100.
    EXPECT_DOUBLE_EQ(q.nedt_temperature_k, 303.15);
    const double expected = kNoise / (100.0 * kBand.radiance_dT(303.15));
    EXPECT_NEAR(q.nedt_median_k, expected, 0.02 * expected);
}

TEST(CalibrationQuality, ApplyingBeyondTheCalibratedRangeWarnsWithTheRange) {
    const DriftingCameraTruth truth(DriftingCamera{});
    std::vector<BlackbodyFrame> frames;
    unsigned seed = 1;
    for (double fpa : {298.0, 308.0})
        for (double t : kSetPointsK) frames.push_back(truth.frame(kBand, t, fpa, ++seed));
    RadiometricOptions options;
    options.fpa_degree = 1;
    const auto cal = fit_radiometric(frames, kW, kH, kBand, options);
    auto radiance_of = [&](double scene_k, double fpa_k) {
        return counts_to_radiance(cal, truth.frame(kBand, scene_k, fpa_k, 99).counts, fpa_k);
    };
    EXPECT_FALSE(extrapolation_warning(cal, radiance_of(300.0, 303.0), 303.0));
    const auto cold = extrapolation_warning(cal, radiance_of(250.0, 303.0), 303.0);
    ASSERT_TRUE(cold);
    EXPECT_THAT(*cold, testing::HasSubstr("283.15–333.15 K"));
    EXPECT_THAT(*cold, testing::HasSubstr(fmt::format("{} below", kW * kH)));
    // The same count as a fraction, for the Stokes EXR's calibration_outside_range_fraction.
    EXPECT_EQ(outside_calibrated_range_fraction(cal, radiance_of(250.0, 303.0)), 1.0);
    EXPECT_EQ(outside_calibrated_range_fraction(cal, radiance_of(300.0, 303.0)), 0.0);
    auto half = radiance_of(300.0, 303.0);
    const auto cold_half = radiance_of(250.0, 303.0);
    for (std::size_t i = 0; i < half.size() / 2; ++i) half[i] = cold_half[i];
    std::size_t good = 0, good_cold = 0;
    for (std::size_t i = 0; i < half.size(); ++i) {
        if (cal.bad[i] != 0.0f) continue;
        ++good;
        good_cold += i < half.size() / 2;
    }
    EXPECT_NEAR(outside_calibrated_range_fraction(cal, half),
                static_cast<double>(good_cold) / static_cast<double>(good), 1e-12);
    const auto hot_camera = extrapolation_warning(cal, radiance_of(300.0, 315.0), 315.0);
    ASSERT_TRUE(hot_camera);
    EXPECT_THAT(*hot_camera,
                testing::HasSubstr("FPA temperature 315.00 K is outside the calibrated FPA range"));
}

TEST(CalibrationQuality, SummaryWritesPageAndMaps) {
    const auto frames = curved_camera_frames(0.03, 4);
    const auto cal = fit_radiometric(frames, kW, kH, kBand);
    const auto q = assess_calibration(cal, frames);
    test::TempDir dir;
    write_calibration_summary(dir / "cal.summary", cal, q);
    for (const char* f : {"index.html", "maps.exr", "nedt.png", "bad_pixels.png", "residuals.png"})
        EXPECT_TRUE(std::filesystem::is_regular_file(dir / "cal.summary" / f)) << f;
    const std::string html = read_file(dir / "cal.summary" / "index.html");
    EXPECT_THAT(html, testing::HasSubstr("--quadratic"));
    EXPECT_THAT(html, testing::HasSubstr("283.15–333.15 K"));
    const Image maps = read_exr(dir / "cal.summary" / "maps.exr");
    EXPECT_EQ(maps.channel("nedt_k"), q.nedt_k);
    EXPECT_EQ(default_summary_dir("/data/cal.exr"), "/data/cal.summary");
}

TEST(CalibrationQuality, ReductionListsRecordsBeyondTheCalibratedRange) {
    // The synthetic scene seen through the polarizer (≈ half of a 280 K scene plus the grid's
    // background) reads below the 283.15–328.15 K laboratory calibration: reduced, but listed.
    test::TempDir root;
    const SyntheticCamera cam;
    write_synthetic_sessions(root.path(), cam, synthetic_panel_scene(cam.width, cam.height, kBand),
                             kBand);
    const auto cal = calibrate_radiometric_session(root / "lab", kBand);
    const Image s = reduce_session(root / "scene", cal, nullptr);
    ASSERT_TRUE(s.attributes().count("calibration_warnings"));
    const auto& text = std::get<std::string>(s.attributes().at("calibration_warnings"));
    EXPECT_THAT(text, testing::HasSubstr("frames/scene_45.0deg.exr: "));
    EXPECT_THAT(text, testing::HasSubstr("outside the calibrated blackbody range 283.15–328.15 K"));

    // The shutter's offset update is in the output with its uncertainty: the synthetic field drift
    // is 60 counts; σ of a 16-frame mean of 6-count noise is 1.5 counts ≈ 21 mK at 293 K.
    SessionReductionOptions update;
    update.update_offset = true;
    const Image u = reduce_session(root / "scene", cal, nullptr, update);
    const auto attr = [&](const char* name) { return std::get<double>(u.attributes().at(name)); };
    EXPECT_NEAR(attr("offset_update_mean_counts"), cam.field_offset_drift, 0.5);
    EXPECT_NEAR(attr("offset_update_sigma_counts"), cam.noise_counts / std::sqrt(cam.frames), 1e-3);
    EXPECT_NEAR(attr("offset_update_sigma_mk"),
                1e3 * 1.5 / (cam.gain_mean * kBand.radiance_dT(293.15)), 1.5);
    EXPECT_THAT(std::get<std::string>(u.attributes().at("offset_update_source")),
                testing::HasSubstr("shutter"));
}

}  // namespace
}  // namespace tirpol::calibration
