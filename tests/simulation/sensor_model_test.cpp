// The sensor model (digital twin of the field camera): Malus's law through a non-ideal analyzer,
// the reduction of eqs 14–16 recovering the Stokes vector scaled by the analyzer's diattenuation,
// the wire-grid background term, and counts whose temporal noise matches the NEDT.

#include "tirpol/simulation/sensor_model.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tirpol/core/config.h"
#include "tirpol/core/stokes.h"

namespace tirpol::simulation {
namespace {

Image stokes_image(const StokesVector& s, int w = 64, int h = 64) {
    Image img(w, h);
    const char* names[4] = {"S0", "S1", "S2", "S3"};
    for (int c = 0; c < 4; ++c) img.add_channel(names[c], static_cast<float>(s[c]));
    return img;
}

TEST(SensorModel, NonIdealAnalyzerFollowsMalusAndEqs14To16) {
    const StokesVector s(10.0, -1.5, 0.8, 0.0);
    SensorModel m;
    m.analyzer.transmission = 0.7;
    m.analyzer.extinction_ratio = 400.0;  // the paper's wire grid (§3.1)
    const auto frames = polarizer_images(stokes_image(s), m, Band(8.0, 14.0));
    ASSERT_EQ(frames.size(), 4u);
    const double i0 = frames[0].at("radiance", 3, 3), i45 = frames[1].at("radiance", 3, 3);
    const double i90 = frames[2].at("radiance", 3, 3), i135 = frames[3].at("radiance", 3, 3);
    // Diattenuator: I(α) = ½[(τ + τ_min)S0 + (τ − τ_min)(S1 cos2α + S2 sin2α)] (Chipman et al. 2018
    // eq 6.35).
    const double t = 0.7, tmin = 0.7 / 400.0;
    EXPECT_NEAR(i0, 0.5 * ((t + tmin) * s[0] + (t - tmin) * s[1]), 1e-5);
    EXPECT_NEAR(i45, 0.5 * ((t + tmin) * s[0] + (t - tmin) * s[2]), 1e-5);
    // eqs 14–16 then give S0·(τ + τ_min) and S1, S2·(τ − τ_min).
    EXPECT_NEAR(0.5 * (i0 + i45 + i90 + i135), (t + tmin) * s[0], 1e-4);
    EXPECT_NEAR(i0 - i90, (t - tmin) * s[1], 1e-5);
    EXPECT_NEAR(i45 - i135, (t - tmin) * s[2], 1e-5);
}

TEST(SensorModel, AngleOffsetRotatesTheAnalyzer) {
    SensorModel m;
    m.analyzer.extinction_ratio = 1e9;
    m.analyzer.transmission = 1.0;
    m.analyzer.angle_offset_deg = 45.0;
    // Light polarized at 45°: through "0°" (really 45°) it passes entirely.
    const auto frames =
        polarizer_images(stokes_image(StokesVector(1, 0, 1, 0)), m, Band(8.0, 14.0));
    EXPECT_NEAR(frames[0].at("radiance", 0, 0), 1.0, 1e-6);
    EXPECT_NEAR(frames[2].at("radiance", 0, 0), 0.0, 1e-6);
}

TEST(SensorModel, BackgroundAndCountsNoiseMatchTheNedt) {
    const Band band(8.0, 14.0);
    const SensorModel m = SensorModel::from_config(
        ConfigNode::parse("analyzer: {transmission: 1.0, extinction_ratio: 1.0e9}\n"
                          "background: {reflectance: 0.1, reflected_radiance: 5.0, emissivity: "
                          "0.05, temperature: \"20 °C\"}\n"
                          "counts: {gain_counts_per_radiance: 200, offset_counts: 1000, nedt_k: "
                          "0.8, reference_temperature: 300}\n"
                          "seed: 3\n"));
    const StokesVector s(30.0, 0.0, 0.0, 0.0);
    const auto frames = polarizer_images(stokes_image(s, 128, 128), m, band);
    const double background = 0.1 * 5.0 + 0.05 * band.radiance(293.15);
    EXPECT_NEAR(frames[0].at("radiance", 0, 0), 15.0 + background, 1e-4);
    const auto& counts = frames[0].channel("counts");
    const ChannelStats st = channel_stats(counts);
    const double sigma = 200.0 * 0.8 * band.radiance_dT(300.0);
    EXPECT_NEAR(st.mean, 200.0 * (15.0 + background) + 1000.0, 5.0 * sigma / 128.0);
    EXPECT_NEAR(st.std / sigma, 1.0, 0.03);  // 16384 samples: std of the std ≈ 0.6 %
    // Deterministic for a seed; another frame index is another noise realisation.
    EXPECT_EQ(polarizer_images(stokes_image(s, 128, 128), m, band)[0].channel("counts"), counts);
    EXPECT_NE(polarizer_images(stokes_image(s, 128, 128), m, band, 1)[0].channel("counts"), counts);
}

}  // namespace
}  // namespace tirpol::simulation
