// The counts → kelvin noise analysis (`tirpol noise`): NEDT = temporal σ in counts / (gain·dL/dT)
// at the blackbody temperature, the calibration's bad pixels are left out of the NEDT statistics
// (responsivity 0, NEDT NaN), and the report holds the kelvin half only with a calibration.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tirpol/calibration/noise.h"
#include "tirpol/core/error.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::calibration {
namespace {

constexpr int kW = 24, kH = 16, kFrames = 32;
constexpr double kGain = 100.0, kOffset = 5000.0, kSigmaCounts = 8.0, kTemperatureK = 300.0;
constexpr std::size_t kBadPixel = 5 * kW + 7;

RadiometricCalibration linear_calibration() {
    RadiometricCalibration cal;
    cal.width = kW;
    cal.height = kH;
    const std::size_t n = static_cast<std::size_t>(kW * kH);
    cal.gain.assign(n, static_cast<float>(kGain));
    cal.offset.assign(n, static_cast<float>(kOffset));
    cal.bad.assign(n, 0.0f);
    cal.bad[kBadPixel] = 1.0f;
    cal.band_lo_um = 8.0;
    cal.band_hi_um = 14.0;
    return cal;
}

FrameStack blackbody_stack(unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, kSigmaCounts);
    const double counts = kOffset + kGain * Band(8.0, 14.0).radiance(kTemperatureK);
    FrameStack s{kW, kH, {}};
    for (int t = 0; t < kFrames; ++t) {
        std::vector<float> f(static_cast<std::size_t>(kW * kH));
        for (auto& v : f) v = static_cast<float>(counts + noise(rng));
        s.frames.push_back(std::move(f));
    }
    return s;
}

TEST(NoiseReport, KelvinStackResponsivityIsOneAtGoodPixelsAndZeroAtBadOnes) {
    const auto r = kelvin_stack_responsivity(linear_calibration());
    ASSERT_EQ(r.size(), static_cast<std::size_t>(kW * kH));
    EXPECT_EQ(r[kBadPixel], 0.0f);
    EXPECT_EQ(r[0], 1.0f);
}

TEST(NoiseReport, NedtIsCountsNoiseOverGainTimesRadianceSlope) {
    const auto cal = linear_calibration();
    const auto a = analyse_noise(blackbody_stack(7), &cal, {});
    ASSERT_TRUE(a.kelvin.has_value());
    const double expected_k = kSigmaCounts / (kGain * Band(8.0, 14.0).radiance_dT(kTemperatureK));
    EXPECT_NEAR(a.kelvin->nedt_median_k, expected_k, 0.1 * expected_k);
    EXPECT_NEAR(a.temporal_noise_median_counts, kSigmaCounts, 0.1 * kSigmaCounts);
    EXPECT_NEAR(a.kelvin->mean_brightness_temperature_k, kTemperatureK, 0.05);
    // No temperature given: the brightness temperature is reported.
    EXPECT_EQ(a.kelvin->blackbody_temperature_k, a.kelvin->mean_brightness_temperature_k);
    EXPECT_TRUE(std::isnan(a.kelvin->nedt_k[kBadPixel]));
    EXPECT_TRUE(std::isfinite(a.kelvin->nedt_k[0]));
    // n = 1, 2, 4, 8 (at least 4 independent means of 32 frames); white noise falls as 1/√n.
    ASSERT_EQ(a.kelvin->nedt_vs_frames_averaged.size(), 4u);
    const auto& last = a.kelvin->nedt_vs_frames_averaged.back();
    EXPECT_NEAR(last.median_nedt_k, last.white_noise_k, 0.3 * last.white_noise_k);
}

TEST(NoiseReport, JsonHoldsTheKelvinHalfOnlyWithACalibration) {
    const auto stack = blackbody_stack(8);
    const auto counts_only = noise_analysis_json(analyse_noise(stack, nullptr, {}), "stack/");
    EXPECT_EQ(counts_only["frames"].get<int>(), kFrames);
    EXPECT_EQ(counts_only["stack"].get<std::string>(), "stack/");
    EXPECT_EQ(counts_only["convention"].get<std::string>().rfind("sample", 0), 0u);
    EXPECT_NEAR(counts_only["three_d_noise_counts"]["sigma_tvh"].get<double>(), kSigmaCounts, 0.8);
    EXPECT_FALSE(counts_only.contains("nedt_median_k"));

    const auto cal = linear_calibration();
    NoiseAnalysisOptions options;
    options.blackbody_temperature_k = 300.5;
    const auto with_cal = noise_analysis_json(analyse_noise(stack, &cal, options), "stack/");
    EXPECT_EQ(with_cal["temperature_k"].get<double>(), 300.5);
    EXPECT_EQ(with_cal["nedt_vs_frames_averaged"].size(), 4u);
    EXPECT_TRUE(with_cal.contains("three_d_noise_k"));
}

TEST(NoiseReport, CalibrationOfAnotherSizeIsRejected) {
    auto cal = linear_calibration();
    cal.width = kW / 2;
    EXPECT_THROW(analyse_noise(blackbody_stack(9), &cal, {}), Error);
}

}  // namespace
}  // namespace tirpol::calibration
