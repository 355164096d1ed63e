// The twin's blackbody set-points bracket what its camera sees: the radiometric ones (polarizer
// out) the detector radiance of the scene through the polarizer, ½(τ + τ_min)S0 ± ½(τ − τ_min)|S12|
// + B (the sensor model's Malus law, Chipman, Lam & Young 2018 eq 6.35), the polarimetric ones the
// scene's S0; beyond the laboratory's blackbodies they are clamped and the reason is given.

#include <gtest/gtest.h>

#include <cmath>

#include "tirpol/twin/instrument.h"
#include "tirpol/twin/twin.h"

namespace tirpol::twin {
namespace {

Image stokes_image(double s0_lo, double s0_hi, double dolp) {
    Image s(8, 4);
    auto& s0 = s.add_channel("S0");
    auto& s1 = s.add_channel("S1");
    auto& s2 = s.add_channel("S2");
    s.add_channel("S3");
    for (std::size_t i = 0; i < s0.size(); ++i) {
        const double t = static_cast<double>(i) / static_cast<double>(s0.size() - 1);
        s0[i] = static_cast<float>(s0_lo + t * (s0_hi - s0_lo));
        s1[i] = static_cast<float>(-dolp * s0[i] * std::cos(3.0 * t));
        s2[i] = static_cast<float>(dolp * s0[i] * std::sin(3.0 * t));
    }
    s0[3] = std::numeric_limits<float>::quiet_NaN();  // missing data is skipped
    return s;
}

TEST(TwinCalibrationSetpoints, BracketTheDetectorRadianceAndTheSceneS0) {
    const Band band(8.0, 14.0);
    const simulation::SensorModel sensor = twin_sensor(band, 283.15);
    // A night scene: S0 from a 250 K sky to a 300 K panel, 5 % polarized.
    const Image scene = stokes_image(band.radiance(250.0), band.radiance(300.0), 0.05);
    const BlackbodySetpoints sp = blackbody_setpoints({scene}, sensor, band);
    ASSERT_EQ(sp.radiometric_k.size(), 3u);
    ASSERT_EQ(sp.polarimetric_k.size(), 2u);
    EXPECT_TRUE(sp.limitation.empty()) << sp.limitation;
    EXPECT_NEAR(sp.scene_s0_min, band.radiance(250.0), 1e-4 * band.radiance(250.0));
    // Polarimetric: the scene's S0 brightness temperatures with the margin.
    EXPECT_NEAR(sp.polarimetric_k[0], 250.0 - kSetpointMarginK, 0.01);
    EXPECT_NEAR(sp.polarimetric_k[1], 300.0 + kSetpointMarginK, 0.01);
    // Radiometric: every detector radiance the scene (at any polarizer angle) and the polarimetric
    // blackbody frames produce lies inside [L(T_lo), L(T_hi)].
    const double tau = sensor.analyzer.transmission,
                 tau_min = tau / sensor.analyzer.extinction_ratio;
    const double b = sensor.background.reflectance * sensor.background.reflected_radiance +
                     sensor.background.emissivity * band.radiance(sensor.background.temperature_k);
    const double l_lo = band.radiance(sp.radiometric_k.front()),
                 l_hi = band.radiance(sp.radiometric_k.back());
    for (std::size_t i = 0; i < scene.pixel_count(); ++i) {
        const double s0 = scene.channel("S0")[i], s1 = scene.channel("S1")[i],
                     s2 = scene.channel("S2")[i];
        if (!std::isfinite(s0)) continue;
        for (double angle_deg : {0.0, 45.0, 90.0, 135.0, 22.5}) {
            const double th = angle_deg * M_PI / 90.0;  // 2θ
            const double l = 0.5 * (tau + tau_min) * s0 +
                             0.5 * (tau - tau_min) * (s1 * std::cos(th) + s2 * std::sin(th)) + b;
            EXPECT_GT(l, l_lo);
            EXPECT_LT(l, l_hi);
        }
    }
    for (double k : sp.polarimetric_k) {
        const double l = 0.5 * (tau + tau_min) * band.radiance(k) + b;
        EXPECT_GT(l, l_lo);
        EXPECT_LT(l, l_hi);
    }
    EXPECT_LT(sp.radiometric_k[0], sp.radiometric_k[1]);
    EXPECT_LT(sp.radiometric_k[1], sp.radiometric_k[2]);
}

TEST(TwinCalibrationSetpoints, BeyondTheLaboratoryTheyAreClampedAndSaySo) {
    const Band band(8.0, 14.0);
    const simulation::SensorModel sensor = twin_sensor(band, 283.15);
    // A 120 K scene (far below any laboratory blackbody) and a 420 K one.
    const BlackbodySetpoints sp = blackbody_setpoints(
        {stokes_image(band.radiance(120.0), band.radiance(420.0), 0.0)}, sensor, band);
    EXPECT_EQ(sp.radiometric_k.front(), kColdestBlackbodyK);
    EXPECT_EQ(sp.polarimetric_k.back(), kWarmestBlackbodyK);
    EXPECT_NE(sp.limitation.find("clamped"), std::string::npos) << sp.limitation;
    EXPECT_THROW(blackbody_setpoints({Image(2, 2)}, sensor, band), std::exception);
}

}  // namespace
}  // namespace tirpol::twin
