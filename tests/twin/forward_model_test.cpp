// One forward instrument model (core instrument_model.h): simulation's sensor model, calibration's
// synthetic sessions and the twin's camera turn the same Stokes image into the same counts, bit for
// bit, once the synthetic camera's extras (vignetting, ghost, polarized sky, pixel spread, noise)
// are off — and those counts follow the diattenuator's Malus law, C = o + g·(½(τ + τ_min) S0 + ½(τ
// − τ_min)(S1 cos 2θ + S2 sin 2θ) + B) (Chipman, Lam & Young 2018 eq 6.35).

#include <gtest/gtest.h>

#include <cmath>

#include "tirpol/calibration/synthetic_session.h"
#include "tirpol/core/geometry.h"
#include "tirpol/simulation/sensor_model.h"
#include "tirpol/twin/instrument.h"

namespace tirpol {
namespace {

constexpr int kWidth = 16, kHeight = 12;

/// A scene with every pixel polarized differently: S0 from 5 to 45 W/(m²·sr), DoLP up to 0.3.
Image varied_scene() {
    Image s(kWidth, kHeight);
    auto& s0 = s.add_channel("S0");
    auto& s1 = s.add_channel("S1");
    auto& s2 = s.add_channel("S2");
    s.add_channel("S3");
    for (std::size_t i = 0; i < s0.size(); ++i) {
        const double l = 5.0 + 40.0 * static_cast<double>(i) / static_cast<double>(s0.size());
        const double aop = 0.1 * static_cast<double>(i);
        s0[i] = static_cast<float>(l);
        s1[i] = static_cast<float>(0.3 * l * std::cos(2.0 * aop));
        s2[i] = static_cast<float>(0.3 * l * std::sin(2.0 * aop));
    }
    return s;
}

calibration::SyntheticCamera plain_synthetic_camera() {
    calibration::SyntheticCamera cam;
    cam.width = kWidth, cam.height = kHeight;
    cam.gain_rel_std = 0.0, cam.offset_std = 0.0, cam.noise_counts = 0.0;
    cam.vignetting = 0.0, cam.ghost_radiance = 0.0, cam.sky_polarization = 0.0;
    cam.bits_per_pixel = 24;  // no clipping
    // The planted bad pixels, in a corner the comparison leaves out.
    cam.dead_x = 0, cam.dead_y = 0, cam.hot_x = 1, cam.hot_y = 0, cam.noisy_x = 2, cam.noisy_y = 0;
    return cam;
}

/// The sensor model with the synthetic camera's polarizer, grid and detector.
simulation::SensorModel matching_sensor(const calibration::SyntheticCamera& cam, const Band& band) {
    simulation::SensorModel m;
    m.analyzer.transmission = cam.t_max;
    m.analyzer.extinction_ratio = cam.extinction_ratio;
    m.analyzer.angle_offset_deg = cam.angle_offset_deg;
    m.background = {cam.grid_reflectance, band.radiance(cam.sky_temperature_k), cam.grid_emissivity,
                    cam.grid_temperature_k};
    m.counts = simulation::CountsModel{cam.gain_mean, cam.offset_mean, 0.0, 300.0};
    return m;
}

TEST(ForwardInstrumentModel, SensorModelSyntheticSessionAndTwinAgreeExactly) {
    const Band band(8.0, 14.0);
    const Image scene = varied_scene();
    const auto cam = plain_synthetic_camera();
    simulation::SensorModel sensor = matching_sensor(cam, band);
    const twin::TwinWorld world(sensor, band, kWidth, kHeight);
    for (double angle_deg : {0.0, 30.0, 45.0, 90.0, 135.0}) {
        SCOPED_TRACE(angle_deg);
        sensor.analyzer.angles_deg = {angle_deg};
        const auto simulated =
            simulation::polarizer_images(scene, sensor, band).front().channel("counts");
        const auto synthetic =
            calibration::synthetic_record_frame(cam, scene, band, angle_deg, true, false, 7)
                .channel("counts");
        const auto twin_counts = world.sensor_frame(scene, angle_deg, true, 1);
        const double theta = deg_to_rad(angle_deg + cam.angle_offset_deg);
        const double tau_min = cam.t_max / cam.extinction_ratio;
        const double background = cam.grid_reflectance * band.radiance(cam.sky_temperature_k) +
                                  cam.grid_emissivity * band.radiance(cam.grid_temperature_k);
        for (std::size_t i = 3; i < simulated.size();
             ++i) {  // pixels 0–2 hold the planted bad pixels
            ASSERT_EQ(simulated[i], synthetic[i]) << "pixel " << i;
            ASSERT_EQ(simulated[i], twin_counts[i]) << "pixel " << i;
            const double s0 = scene.channel("S0")[i], s1 = scene.channel("S1")[i],
                         s2 = scene.channel("S2")[i];
            const double malus =
                0.5 * (cam.t_max + tau_min) * s0 +
                0.5 * (cam.t_max - tau_min) * (s1 * std::cos(2 * theta) + s2 * std::sin(2 * theta));
            EXPECT_NEAR(simulated[i], cam.offset_mean + cam.gain_mean * (malus + background),
                        1e-3 * simulated[i]);
        }
    }
}

}  // namespace
}  // namespace tirpol
