// An unattended radiometric calibration end to end: the Fluke 4180 driver talks
// to the blackbody simulator on a pseudo-terminal (first-order plate, τ = 0.5 s so the test takes
// seconds rather than the hours of a real 4180), a free-running simulated camera's counts follow
// the plate's *actual*, lagging temperature, counts = offset + gain·L(T_plate) per pixel (L: 8–14
// µm band radiance), run_capture sets each set-point, waits for stability and records the
// controller's readings; the calibration reads that session as `tirpol calibrate radiometric` does,
// and brightness temperatures of a new set-point come back within 30 mK. A second test shows that
// frames taken right after the set-point command, labelled with the set-point, bias the same
// calibration by kelvins.

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "../acquisition/pty_device_thread.h"
#include "test_support.h"
#include "tirpol/acquisition/blackbody.h"
#include "tirpol/acquisition/capture.h"
#include "tirpol/acquisition/internal/blackbody_simulator.h"
#include "tirpol/acquisition/internal/blackbody_wait.h"
#include "tirpol/acquisition/internal/sim_stage.h"
#include "tirpol/acquisition/sim/simulated_camera.h"
#include "tirpol/calibration/session_calibration.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::acquisition {
namespace {

using Clock = PtyDevice::Clock;
constexpr int kWidth = 16, kHeight = 12;
constexpr double kNoiseCounts = 3.0;
const std::vector<double> kSetPointsK{288.15, 298.15, 308.15, 318.15};
constexpr double kCheckK = 303.15;  ///< between the set-points, not one of them

BlackbodySimulatorOptions plate() {
    BlackbodySimulatorOptions o;
    o.time_constant_s = 0.5;
    // Sensor noise well inside the 10 mK tolerance (≥ 4σ of margin once the plate has settled): a
    // reading during the frames outside it fails the step, as it should on a real controller.
    o.noise_k = 0.001;
    o.stability_limit_k = 0.01;
    o.stability_window_s = 0.3;
    o.sample_period_s = 0.02;
    return o;
}

/// The rig: blackbody on a pty, a sim:// stage, a 60 Hz camera looking at the plate with per-pixel
/// gain (≈ 400 counts per W/(m²·sr), ±10 %: the 8–14 µm radiance is 57.6 W/(m²·sr) at 303 K
/// and 71.4 at 318 K, so ≤ 34000 counts, well below the 16-bit ceiling) and offset (≈ 2000 counts,
/// ±300).
struct Rig {
    test::PtyDeviceThread<BlackbodySimulator> sim{plate()};
    std::unique_ptr<BlackbodyController> blackbody =
        open_blackbody("fluke-4180://" + sim.path() + "?timeout_ms=5000")  // a loaded CI machine
            .value_or_throw();
    std::unique_ptr<Stage> stage = make_simulated_stage("sim://");
    Band band{8.0, 14.0};
    std::vector<float> gain, offset;
    std::unique_ptr<SimulatedCamera> camera;

    Rig() {
        for (int i = 0; i < kWidth * kHeight; ++i) {
            gain.push_back(static_cast<float>(400.0 * (0.9 + 0.2 * ((i * 37) % 101) / 100.0)));
            offset.push_back(static_cast<float>(2000.0 + 300.0 * std::sin(i * 0.7)));
        }
        SimulatedCameraConfig config;
        config.width = kWidth;
        config.height = kHeight;
        config.frame_rate_hz = 60.0;
        config.noise_std_counts = kNoiseCounts;
        config.fpa_temperature_k = 305.0;
        config.seed = 11;
        camera =
            std::make_unique<SimulatedCamera>(config, [this](double, std::vector<float>& counts) {
                const double radiance =
                    band.radiance(sim.device().plate_temperature_k(Clock::now()));
                for (std::size_t i = 0; i < counts.size(); ++i)
                    counts[i] = static_cast<float>(offset[i] + gain[i] * radiance);
            });
    }

    /// Mean of `n` frames from now on.
    std::vector<float> average_frames(int n) {
        std::vector<float> sum(static_cast<std::size_t>(kWidth * kHeight), 0.0f);
        for (int k = 0; k < n; ++k) {
            const Frame f = camera->grab(std::chrono::seconds(5)).value_or_throw();
            for (std::size_t i = 0; i < sum.size(); ++i)
                sum[i] += f.counts[i] / static_cast<float>(n);
        }
        return sum;
    }

    /// Brightness temperatures (K) of the plate held stable at kCheckK, through `cal`, and the
    /// plate's true temperature.
    std::pair<std::vector<float>, double> check_temperatures(
        const calibration::RadiometricCalibration& cal) {
        bring_blackbody_to(*blackbody, kCheckK, {0.01, 0.3, 30.0, 0.05}).value_or_throw();
        ensure_streaming();
        const double truth = sim.device().plate_temperature_k(Clock::now());
        const auto radiance = calibration::counts_to_radiance(cal, average_frames(32));
        return {calibration::brightness_temperature(band, radiance), truth};
    }

    void ensure_streaming() {
        if (!m_streaming) camera->start().value_or_throw();
        m_streaming = true;
        // Drop what queued before now: those frames saw an earlier plate.
        while (camera->grab(std::chrono::milliseconds(0))) {
        }
    }
    bool m_streaming = false;
};

double max_abs_error(const std::vector<float>& t, double truth) {
    double worst = 0.0;
    for (float v : t) worst = std::max(worst, std::abs(v - truth));
    return worst;
}

TEST(BlackbodyCalibration, UnattendedSessionCalibratesToWithin30mK) {
    test::TempDir tmp;
    Rig rig;
    const CapturePlan plan = CapturePlan::parse(ConfigNode::parse(R"(
angles_deg: [0]
frames_per_angle: 2
settle_s: 0
references:
  - kind: blackbody
    temperatures_k: [288.15, 298.15, 308.15, 318.15]
    frames: 24
    controller: {tolerance_k: 0.01, stable_for_s: 0.3, timeout_s: 30, poll_s: 0.05}
metadata: {polarizer_in_beam: false}
)",
                                                                  "plan.yaml"));
    const BlackbodyInfo bb_info = rig.blackbody->info();
    {
        auto session = SessionWriter::create(
            tmp / "s", new_session_manifest(rig.camera->info(), rig.stage->info(), plan, &bb_info));
        CaptureOptions options;
        options.progress_stream = nullptr;
        options.blackbody = rig.blackbody.get();
        const CaptureSummary summary = run_capture(*rig.camera, *rig.stage, plan, session, options);
        EXPECT_EQ(summary.steps_recorded, 5u);
    }

    // The session records what the controller read during each record's frames.
    const SessionManifest m = read_session(tmp / "s");
    ASSERT_TRUE(m.blackbody_controller);
    EXPECT_EQ(m.blackbody_controller->model, "4180");
    for (std::size_t i = 0; i < kSetPointsK.size(); ++i) {
        const SessionRecord& r = m.records[i];
        ASSERT_TRUE(r.blackbody_readings) << r.file;
        EXPECT_DOUBLE_EQ(r.blackbody_readings->set_point_k, kSetPointsK[i]);
        EXPECT_NEAR(r.blackbody_readings->mean_k, kSetPointsK[i], 0.01) << r.file;
        EXPECT_GE(r.blackbody_readings->readings, 2);
        EXPECT_GT(r.blackbody_readings->wait_s, 0.3);  // at least the hold
        EXPECT_DOUBLE_EQ(*r.blackbody_temperature_k, r.blackbody_readings->mean_k);
    }
    EXPECT_FALSE(m.records.back().blackbody_readings);  // the polarizer record

    const auto cal = calibration::calibrate_radiometric_session(tmp / "s", rig.band);
    const auto [temperatures, truth] = rig.check_temperatures(cal);
    std::printf(
        "brightness temperature error at %.2f K after the unattended session: max %.4f K over %d "
        "pixels\n",
        kCheckK, max_abs_error(temperatures, truth), kWidth * kHeight);
    // Budget: 3 counts of noise over 24 + 32 frames ≈ 0.6 + 0.5 counts, ≈ 3 mK at ≈ 350 counts/K,
    // the controller's 1 mK sensor noise and the ±10 mK tolerance the plate held: 30 mK bounds it.
    EXPECT_LT(max_abs_error(temperatures, truth), 0.03);
}

TEST(BlackbodyCalibration, CapturingBeforeTheSetPointIsStableBiasesTheCalibration) {
    // The same rig, without the wait: frames right after each set-point command, labelled with it
    // (what a script that does not wait records). The plate lags by τ, so the labels are wrong by
    // kelvins and so is the calibration. Then the same set-points with the wait, for comparison.
    Rig rig;
    rig.ensure_streaming();
    auto fit = [&](bool wait) {
        std::vector<calibration::BlackbodyFrame> frames;
        for (double t : kSetPointsK) {
            if (wait)
                bring_blackbody_to(*rig.blackbody, t, {0.01, 0.3, 30.0, 0.05}).value_or_throw();
            else
                rig.blackbody->set_temperature_k(t).value_or_throw();
            rig.ensure_streaming();
            calibration::BlackbodyFrame f;
            f.temperature_k = t;
            f.counts = rig.average_frames(24);
            f.frames = 24;
            frames.push_back(std::move(f));
        }
        return calibration::fit_radiometric(frames, kWidth, kHeight, rig.band);
    };
    const auto hasty = fit(false);
    const auto patient = fit(true);
    const auto [hasty_t, truth_hasty] = rig.check_temperatures(hasty);
    const double hasty_error = max_abs_error(hasty_t, truth_hasty);
    const auto [patient_t, truth_patient] = rig.check_temperatures(patient);
    const double patient_error = max_abs_error(patient_t, truth_patient);
    std::printf("brightness temperature error at %.2f K: without the wait %.3f K, with it %.4f K\n",
                kCheckK, hasty_error, patient_error);
    EXPECT_GT(hasty_error, 1.0);
    EXPECT_LT(patient_error, 0.03);
}

}  // namespace
}  // namespace tirpol::acquisition
