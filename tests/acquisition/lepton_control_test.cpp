// The Lepton on a PureThermal board: its CCI commands encoded into UVC extension-unit controls
// (IDD 110-0144 command ids; PureThermal/GetThermal unit and selector mapping) and the FFC and
// telemetry logic, tested against MockPureThermalLepton: a simulated Lepton answering at the
// extension-unit seam, where the real system has the kernel's UVCIOC_CTRL_QUERY ioctl (not
// reachable without the board). The capture then schedules and detects the Lepton's FFCs through
// the same FfcControl interface as the Boson's.

#include "tirpol/acquisition/internal/lepton_control.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>
#include <thread>

#include "mock_purethermal_lepton.h"
#include "session_angle_means.h"
#include "test_support.h"
#include "tirpol/acquisition/capture.h"
#include "tirpol/acquisition/internal/sim_stage.h"
#include "tirpol/acquisition/sim/simulated_camera.h"
#include "tirpol/core/session.h"

namespace tirpol::acquisition {
namespace {

using ::testing::HasSubstr;
using Bytes = std::vector<std::uint8_t>;
using test::MockPureThermalLepton;

TEST(LeptonCci, CommandIdsMapToPureThermalUnitsAndSelectors) {
    // Units: AGC 3, OEM 4, RAD 5, SYS 6, VID 7; selector ((id & 0xFF) >> 2) + 1 (GetThermal).
    EXPECT_EQ(lepton::xu_unit(lepton::kSysFfcShutterMode), 6);
    EXPECT_EQ(lepton::xu_selector(lepton::kSysFfcShutterMode), 16);  // 0x3C / 4 + 1
    EXPECT_EQ(lepton::xu_selector(lepton::kSysRunFfc), 17);
    EXPECT_EQ(lepton::xu_selector(0x0242), 17);  // the RUN type bits do not change the selector
    EXPECT_EQ(lepton::xu_unit(lepton::kRadTLinearEnable), 5);
    EXPECT_EQ(lepton::xu_selector(lepton::kRadTLinearEnable), 49);
    EXPECT_EQ(lepton::xu_selector(lepton::kRadTLinearResolution), 50);
    EXPECT_EQ(lepton::xu_unit(0x4E10), 5);  // the OEM bit of RAD commands is ignored
    EXPECT_EQ(lepton::xu_unit(0x0100), 3);
    EXPECT_EQ(lepton::xu_unit(0x0804), 4);
    EXPECT_EQ(lepton::xu_unit(0x0300), 7);
    EXPECT_FALSE(lepton::xu_unit(0x0500));
}

TEST(LeptonCci, ShutterModeObjectIsSixteenLittleEndianWordsAndRoundTrips) {
    lepton::FfcShutterMode m;
    m.mode = lepton::FfcShutterMode::External;
    m.desired_ffc_period_ms = 0x00012345;
    m.desired_ffc_temp_delta_centi_k = 150;
    const auto words = lepton::encode_ffc_shutter_mode(m);
    ASSERT_EQ(words.size(), 16u);
    const auto bytes = lepton::words_to_bytes(words);
    EXPECT_EQ((Bytes{bytes[0], bytes[1], bytes[2], bytes[3]}), (Bytes{2, 0, 0, 0}));
    // desiredFfcPeriod: words 10–11, less significant word first.
    EXPECT_EQ((Bytes{bytes[20], bytes[21], bytes[22], bytes[23]}), (Bytes{0x45, 0x23, 0x01, 0x00}));
    EXPECT_EQ(lepton::decode_ffc_shutter_mode(lepton::bytes_to_words(bytes)), m);
    EXPECT_FALSE(lepton::decode_ffc_shutter_mode(std::vector<std::uint16_t>(15, 0)));
}

TEST(LeptonCci, TelemetryRowAGivesFpaTemperatureFrameCounterAndTheLastFfc) {
    lepton::Telemetry t;
    t.uptime_ms = 0x0001F000;
    t.frame_counter = 0x00020003;
    t.fpa_temperature_k = 307.15;
    t.uptime_at_last_ffc_ms = 0x0001E000;
    t.status_bits = 2u << 4;
    const auto row = lepton::encode_telemetry(t);
    EXPECT_EQ(row[20], 0x0003);  // frame counter, words 20–21, LSW first
    EXPECT_EQ(row[21], 0x0002);
    EXPECT_EQ(row[24], 30715);  // FPA temperature in K × 100, word 24
    const auto back = lepton::parse_telemetry(row);
    ASSERT_TRUE(back);
    EXPECT_EQ(back->frame_counter, t.frame_counter);
    EXPECT_NEAR(back->fpa_temperature_k, 307.15, 1e-9);
    EXPECT_EQ(back->uptime_at_last_ffc_ms, t.uptime_at_last_ffc_ms);
    EXPECT_EQ(back->ffc_state(), 2);  // in progress
    EXPECT_FALSE(lepton::parse_telemetry(std::span(row).first(20)));
}

TEST(LeptonControl, ManualFfcModeChangesOnlyTheModeOfTheCoresObject) {
    auto xu = std::make_unique<MockPureThermalLepton>();
    auto* lepton = xu.get();
    lepton->shutter.desired_ffc_period_ms = 60000;
    lepton->shutter.desired_ffc_temp_delta_centi_k = 120;
    LeptonControl control(std::move(xu));
    control.set_manual_ffc().value_or_throw();
    EXPECT_EQ(lepton->shutter.mode, lepton::FfcShutterMode::Manual);
    EXPECT_EQ(lepton->shutter.desired_ffc_period_ms, 60000u);
    EXPECT_EQ(lepton->shutter.desired_ffc_temp_delta_centi_k, 120);
    const auto calls = lepton->calls();
    ASSERT_EQ(calls.size(), 2u);  // GET_CUR then SET_CUR of unit 6, selector 16, 32 bytes
    EXPECT_FALSE(calls[0].set);
    EXPECT_TRUE(calls[1].set);
    EXPECT_EQ(calls[1].unit, 6);
    EXPECT_EQ(calls[1].selector, 16);
    EXPECT_EQ(calls[1].bytes.size(), 32u);
}

TEST(LeptonControl, RadiometryTLinearIsSetAndReadBack) {
    auto xu = std::make_unique<MockPureThermalLepton>();
    auto* lepton = xu.get();
    LeptonControl control(std::move(xu));
    control.set_tlinear(true, LeptonTLinearResolution::HundredthKelvin).value_or_throw();
    EXPECT_EQ(lepton->tlinear_enabled, 1u);
    EXPECT_EQ(lepton->tlinear_resolution, 1u);
    EXPECT_TRUE(control.tlinear_enabled().value_or_throw());
    EXPECT_EQ(control.tlinear_resolution().value_or_throw(),
              LeptonTLinearResolution::HundredthKelvin);
    lepton->tlinear_resolution = 7;
    auto bad = control.tlinear_resolution();
    ASSERT_FALSE(bad);
    EXPECT_THAT(bad.error().message, HasSubstr("TLinear resolution 7"));
}

TEST(LeptonControl, RunFfcWaitsUntilTheCoreIsReadyAndTheTelemetryShowsIt) {
    auto xu = std::make_unique<MockPureThermalLepton>();
    auto* lepton = xu.get();
    lepton->busy_polls = 3;
    LeptonControl control(std::move(xu),
                          {std::chrono::milliseconds(200), std::chrono::milliseconds(1)});
    EXPECT_FALSE(control.last_ffc_marker());  // no telemetry within the 200 ms wait
    auto frames = [&](int n) {
        for (int i = 0; i < n; ++i)
            control.observe_telemetry(*lepton::parse_telemetry(lepton->frame().second));
    };
    frames(5);
    const auto marker_before = control.last_ffc_marker().value_or_throw();
    EXPECT_EQ(control.frames_since_ffc().value_or_throw(), 4u);
    {
        // Frames keep coming while the FFC runs, as from a streaming board.
        std::atomic<bool> stop{false};
        std::thread video([&] {
            while (!stop) {
                frames(1);
                std::this_thread::sleep_for(std::chrono::milliseconds(2));
            }
        });
        Status done = control.run_ffc_and_wait();
        stop = true;
        video.join();
        std::move(done).value_or_throw();
    }
    EXPECT_EQ(lepton->ffcs(), 1);  // complete when run_ffc_and_wait returned
    EXPECT_NE(control.last_ffc_marker().value_or_throw(), marker_before);
    const auto since = control.frames_since_ffc().value_or_throw();
    frames(2);
    EXPECT_EQ(control.frames_since_ffc().value_or_throw(), since + 2);
    EXPECT_NEAR(control.fpa_temperature_k().value_or_throw(), 305.42, 1e-9);
    lepton->ffc_fails = true;
    auto failed = control.run_ffc_and_wait();
    ASSERT_FALSE(failed);
    EXPECT_EQ(failed.error().code, DeviceErrorCode::DeviceFault);
}

// --- the capture with a Lepton: FFCs scheduled between cycles, an FFC inside one detected --------

constexpr double kS0 = 8000.0, kS1 = 250.0, kS2 = -150.0;

double scene_counts(double theta_deg) {
    const double t = 2.0 * theta_deg * std::numbers::pi / 180.0;
    return 0.5 * (kS0 + kS1 * std::cos(t) + kS2 * std::sin(t));
}

struct LeptonRig {
    MockPureThermalLepton* lepton = nullptr;
    std::unique_ptr<LeptonControl> control;
    std::unique_ptr<Stage> stage;
    std::unique_ptr<SimulatedCamera> camera;
    LeptonRig() {
        auto xu = std::make_unique<MockPureThermalLepton>();
        lepton = xu.get();
        control = std::make_unique<LeptonControl>(
            std::move(xu),
            LeptonControlOptions{std::chrono::milliseconds(2000), std::chrono::milliseconds(1)});
        SimulatedStageOptions so;
        so.deg_per_s = 720.0;
        stage = make_simulated_stage("sim://", so);
        SimulatedCameraConfig config;
        config.name = "lepton";
        config.width = 8;
        config.height = 6;
        config.frame_rate_hz = 60.0;
        config.buffers = 64;
        camera = std::make_unique<SimulatedCamera>(
            config,
            [this](double angle_deg, std::vector<float>& out) {
                // What the PureThermal driver does with each Y16 frame: hand its telemetry row to
                // the control link.
                auto [offset, row] = lepton->frame();
                control->observe_telemetry(*lepton::parse_telemetry(row));
                std::fill(out.begin(), out.end(),
                          static_cast<float>(scene_counts(angle_deg) + offset));
            },
            simulated_stage_angle_source(*stage));
    }
};

double s1_bias(const std::filesystem::path& dir, int repeat) {
    auto mean = test::polarizer_means_by_angle(dir, repeat);
    return mean[0] - mean[90] - kS1;
}

TEST(LeptonCapture, FfcsRunBetweenCyclesAndAnFfcTheCoreRanInsideACycleIsTakenAgain) {
    test::TempDir tmp;
    LeptonRig rig;
    CapturePlan plan;
    plan.frames_per_angle = 6;
    plan.settle_s = 0.03;
    plan.repeats = 2;
    FfcOptions ffc;
    ffc.control = rig.control.get();
    ffc.schedule = FfcOptions::Schedule::EveryCycle;
    CaptureOptions options;
    options.progress_stream = nullptr;
    options.ffc = &ffc;
    bool provoked = false;  // the core corrects on its own inside cycle 1, at 45°
    options.on_progress = [&](const CaptureProgress& p) {
        if (!provoked && p.event == CaptureProgress::Event::Frame && p.step->repeat == 0 &&
            p.step->angle_deg == 45.0 && p.frames_kept == 3) {
            rig.lepton->ffc_on_its_own();
            provoked = true;
        }
    };
    auto session = SessionWriter::create(
        tmp / "s", new_session_manifest(rig.camera->info(), rig.stage->info(), plan));
    const auto summary = run_capture(*rig.camera, *rig.stage, plan, session, options);
    EXPECT_EQ(rig.lepton->shutter.mode, lepton::FfcShutterMode::Manual);
    ASSERT_TRUE(provoked);
    EXPECT_EQ(summary.ffc_detected, 1);
    EXPECT_EQ(summary.ffc_scheduled, 2 + summary.ffc_detected);  // each cycle and each retake
    const SessionManifest m = read_session(tmp / "s");
    EXPECT_EQ(m.ffc_events.size(),
              static_cast<std::size_t>(summary.ffc_scheduled + summary.ffc_detected));
    // The offset stepped by 40 counts inside cycle 1; the records kept are free of it.
    for (int repeat : {0, 1}) EXPECT_LT(std::abs(s1_bias(tmp / "s", repeat)), 1e-3) << repeat;
}

}  // namespace
}  // namespace tirpol::acquisition
