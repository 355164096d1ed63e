// Radiometric calibration: round trips on a synthetic camera with known gain/offset maps, planted
// bad pixels and temporal noise; the fit must recover the truth within the stated tolerances.

#include "tirpol/calibration/radiometric.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "test_support.h"
#include "tirpol/core/error.h"

namespace tirpol::calibration {
namespace {

constexpr int kW = 48, kH = 40;
constexpr double kNoiseCounts = 4.0;  // per-frame temporal σ
constexpr int kFrames = 16;

struct TruthCamera {
    std::vector<float> gain, offset, noise;
    double quadratic = 0.0;  // global, counts/(W/m²sr)²
    std::size_t dead, hot, noisy, nonlinear;

    explicit TruthCamera(unsigned seed) {
        std::mt19937 rng(seed);
        std::normal_distribution<float> g(100.0f, 5.0f), o(5000.0f, 150.0f);
        for (int i = 0; i < kW * kH; ++i) {
            gain.push_back(g(rng));
            offset.push_back(o(rng));
            noise.push_back(static_cast<float>(kNoiseCounts));
        }
        dead = idx(5, 5);
        hot = idx(10, 7);
        noisy = idx(20, 20);
        nonlinear = idx(30, 30);
        gain[dead] *= 0.05f;
        offset[hot] += 4000.0f;
        noise[noisy] *= 10.0f;
    }
    static std::size_t idx(int x, int y) { return static_cast<std::size_t>(y * kW + x); }

    double counts_of(std::size_t i, double l) const {
        double c = offset[i] + gain[i] * l + quadratic * l * l;
        if (i == nonlinear) c += 2.0 * (l - 40.0) * (l - 40.0);  // a strongly curved response
        return c;
    }

    BlackbodyFrame frame(const Band& band, double t_k, std::mt19937& rng) const {
        BlackbodyFrame f;
        f.temperature_k = t_k;
        f.frames = kFrames;
        f.source = "synthetic blackbody " + std::to_string(t_k) + " K";
        const double l = band.radiance(t_k);
        std::normal_distribution<double> unit(0.0, 1.0);
        for (std::size_t i = 0; i < gain.size(); ++i) {
            // Mean of kFrames frames and its sample std, drawn frame by frame.
            double sum = 0.0, sum2 = 0.0;
            for (int k = 0; k < kFrames; ++k) {
                const double c = counts_of(i, l) + noise[i] * unit(rng);
                sum += c;
                sum2 += c * c;
            }
            const double mean = sum / kFrames;
            f.counts.push_back(static_cast<float>(mean));
            f.counts_std.push_back(static_cast<float>(
                std::sqrt(std::max(0.0, (sum2 - kFrames * mean * mean) / (kFrames - 1)))));
        }
        return f;
    }
};

std::vector<BlackbodyFrame> blackbody_set(const TruthCamera& cam, const Band& band,
                                          std::vector<double> temps, unsigned seed) {
    std::mt19937 rng(seed);
    std::vector<BlackbodyFrame> frames;
    for (double t : temps) frames.push_back(cam.frame(band, t, rng));
    return frames;
}

TEST(Radiometric, RecoversGainAndOffsetMapsAndFindsPlantedBadPixels) {
    const Band band(8.0, 14.0);
    const TruthCamera cam(1);
    const auto frames = blackbody_set(cam, band, {283.15, 298.15, 313.15, 328.15}, 2);
    const auto cal = fit_radiometric(frames, kW, kH, band);

    // σ(frame mean) = 4/√16 = 1 count; over a 25 W/(m²·sr) radiance span the gain's σ is ~0.05
    // counts/(W/m²sr) and the offset's ~2 counts: tolerances are ~6σ.
    double worst_gain = 0.0, worst_offset = 0.0;
    for (std::size_t i = 0; i < cam.gain.size(); ++i) {
        if (i == cam.dead || i == cam.hot || i == cam.noisy || i == cam.nonlinear) continue;
        worst_gain = std::max(
            worst_gain, static_cast<double>(std::abs(cal.gain[i] - cam.gain[i]) / cam.gain[i]));
        worst_offset =
            std::max(worst_offset, static_cast<double>(std::abs(cal.offset[i] - cam.offset[i])));
    }
    EXPECT_LT(worst_gain, 3e-3);
    EXPECT_LT(worst_offset, 15.0);

    // Exactly the planted pixels are bad, each in its class.
    auto bits = [&](std::size_t i) { return static_cast<std::uint32_t>(cal.bad[i]); };
    EXPECT_TRUE(bits(cam.dead) & kDead);
    EXPECT_TRUE(bits(cam.hot) & kHot);
    EXPECT_TRUE(bits(cam.noisy) & kNoisy);
    EXPECT_TRUE(bits(cam.nonlinear) & kNonLinear);
    EXPECT_EQ(cal.bad_count(), 4u);
    EXPECT_FALSE(bits(cam.noisy) & kNonLinear);  // its large residual is its own noise

    // A good pixel's fit quality (RMS residual / σ of the mean) is of order 1 (χ²-like).
    const std::size_t good = TruthCamera::idx(40, 30);
    EXPECT_GT(cal.fit_quality[good], 0.05f);
    EXPECT_LT(cal.fit_quality[good], 3.0f);
}

TEST(Radiometric, SceneRadianceRoundTripGivesBrightnessTemperatureAndReplacesBadPixels) {
    const Band band(8.0, 14.0);
    const TruthCamera cam(3);
    const auto cal = fit_radiometric(blackbody_set(cam, band, {283.15, 298.15, 313.15, 328.15}, 4),
                                     kW, kH, band);
    // A noiseless scene at 305 K seen through the true response.
    const double l = band.radiance(305.0);
    std::vector<float> counts;
    for (std::size_t i = 0; i < cam.gain.size(); ++i)
        counts.push_back(static_cast<float>(cam.counts_of(i, l)));
    const auto t = brightness_temperature(band, counts_to_radiance(cal, counts));
    // dL/dT ≈ 0.7 W/(m²·sr·K) in 8–14 µm at 300 K: a gain error of 3e-3 is ≈ 0.2 K.
    for (std::size_t i = 0; i < t.size(); ++i) ASSERT_NEAR(t[i], 305.0, 0.25) << "pixel " << i;
}

TEST(Radiometric, QuadraticModelRemovesACurvedResponseThatTheLinearModelCannot) {
    const Band band(8.0, 14.0);
    TruthCamera cam(5);
    cam.quadratic = 0.5;
    const auto frames = blackbody_set(cam, band, {273.15, 288.15, 303.15, 318.15, 333.15}, 6);
    RadiometricOptions quad;
    quad.quadratic = true;
    const auto lin_cal = fit_radiometric(frames, kW, kH, band);
    const auto quad_cal = fit_radiometric(frames, kW, kH, band, quad);
    const std::size_t good = TruthCamera::idx(40, 30);
    EXPECT_NEAR(quad_cal.quadratic[good], 0.5, 0.05);
    EXPECT_LT(quad_cal.residual_rms[good], 3.0f);  // noise level (σ of mean = 1 count)
    EXPECT_GT(lin_cal.residual_rms[good], 20.0f);  // curvature left in the residuals
    std::vector<float> counts;
    const double l = band.radiance(300.0);
    for (std::size_t i = 0; i < cam.gain.size(); ++i)
        counts.push_back(static_cast<float>(cam.counts_of(i, l)));
    EXPECT_NEAR(counts_to_radiance(quad_cal, counts)[good], l, 0.02 * band.radiance_dT(300.0));
}

TEST(Radiometric, FieldOffsetUpdateRemovesDrift) {
    const Band band(8.0, 14.0);
    TruthCamera cam(7);
    const auto frames = blackbody_set(cam, band, {283.15, 313.15}, 8);
    auto cal = fit_radiometric(frames, kW, kH, band);
    for (auto& o : cam.offset) o += 80.0f;  // drift of the uncooled camera since the laboratory
    std::mt19937 rng(9);
    update_offset(cal, cam.frame(band, 293.15, rng));
    std::vector<float> counts;
    const double l = band.radiance(300.0);
    for (std::size_t i = 0; i < cam.gain.size(); ++i)
        counts.push_back(static_cast<float>(cam.counts_of(i, l)));
    const auto t = brightness_temperature(band, counts_to_radiance(cal, counts));
    const std::size_t good = TruthCamera::idx(40, 30);
    EXPECT_NEAR(t[good], 300.0, 0.1);  // without the update the 80-count drift is ≈ 1.1 K
}

TEST(Radiometric, CalibrationFileRoundTripsThroughExr) {
    const Band band(8.0, 14.0, SpectralResponse({7.5, 9.0, 13.0, 14.5}, {0.0, 1.0, 1.0, 0.0}));
    const TruthCamera cam(11);
    auto cal =
        fit_radiometric(blackbody_set(cam, band, {283.15, 298.15, 313.15}, 12), kW, kH, band);
    cal.camera_id = "sim:test-camera";
    test::TempDir dir;
    write_radiometric_calibration((dir / "cal.exr").string(), cal);
    const auto back = read_radiometric_calibration((dir / "cal.exr").string());
    EXPECT_EQ(back.gain, cal.gain);
    EXPECT_EQ(back.offset, cal.offset);
    EXPECT_EQ(back.bad, cal.bad);
    // EXR float-vector attributes are 32-bit: temperatures survive to ~1e-5 K.
    ASSERT_EQ(back.temperatures_k.size(), cal.temperatures_k.size());
    for (std::size_t k = 0; k < cal.temperatures_k.size(); ++k)
        EXPECT_NEAR(back.temperatures_k[k], cal.temperatures_k[k], 1e-4);
    EXPECT_EQ(back.rsr_response, cal.rsr_response);
    EXPECT_EQ(back.camera_id, "sim:test-camera");
    EXPECT_NEAR(back.band().radiance(300.0), band.radiance(300.0), 1e-6 * band.radiance(300.0));
}

TEST(Radiometric, BadInputsGiveClearErrors) {
    const Band band(8.0, 14.0);
    const TruthCamera cam(13);
    auto frames = blackbody_set(cam, band, {300.0, 300.0}, 14);
    try {
        fit_radiometric(frames, kW, kH, band);
        FAIL() << "one temperature accepted";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), testing::HasSubstr("1 distinct temperature"));
    }
    frames = blackbody_set(cam, band, {290.0, 310.0}, 15);
    frames[1].counts.pop_back();
    EXPECT_THROW(fit_radiometric(frames, kW, kH, band), Error);
    frames = blackbody_set(cam, band, {290.0, 310.0}, 16);
    frames[0].counts[17] = std::nanf("");
    try {
        fit_radiometric(frames, kW, kH, band);
        FAIL() << "NaN accepted";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), testing::HasSubstr("NaN"));
        EXPECT_THAT(e.what(), testing::HasSubstr("x=17, y=0"));
    }
    frames = blackbody_set(cam, band, {290.0, 310.0}, 17);
    RadiometricOptions sat;
    sat.saturation_counts = 7000.0;  // the 310 K frame reads ≈ 5000 + 100·41 counts: all saturated
    try {
        fit_radiometric(frames, kW, kH, band, sat);
        FAIL() << "saturated frame accepted";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), testing::HasSubstr("saturated"));
    }
}

}  // namespace
}  // namespace tirpol::calibration
