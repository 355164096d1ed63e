// Flat-field corrections and the polarizer cycle, on the simulated Boson core: its video through a
// free-running simulated camera behind the simulated stage, its control link on a pseudo-terminal.
// The scene is linearly polarized (Malus: an ideal polarizer at θ passes (S0 + S1 cos 2θ + S2 sin
// 2θ)/2, paper eqs 14–16). An auto FFC is provoked inside the first cycle by a step of the FPA
// temperature (the core's own threshold logic starts it), at the 45° step's third frame.
// - Without FFC handling that cycle's records carry the shutter and the offset step: S1, S2 biased
//   far beyond the noise.
// - With detection only (no link) the step is found, the cycle taken again, the bias is below
// noise.
// - With the link the core is in manual mode, the FPA step starts no FFC, FFCs run between cycles.

#include <gtest/gtest.h>

#include <cmath>

#include "pty_device_thread.h"
#include "session_angle_means.h"
#include "test_support.h"
#include "tirpol/acquisition/capture.h"
#include "tirpol/acquisition/internal/boson_control.h"
#include "tirpol/acquisition/internal/boson_simulator.h"
#include "tirpol/acquisition/internal/sim_stage.h"
#include "tirpol/acquisition/sim/simulated_camera.h"

namespace tirpol::acquisition {
namespace {

using Clock = std::chrono::steady_clock;

constexpr double kS0 = 10000.0, kS1 = 300.0, kS2 = -200.0;  // counts
constexpr double kNoise = 4.0;                              // temporal noise per frame, counts
constexpr int kFrames = 8;                                  // per angle
constexpr int kWidth = 8, kHeight = 6;

double scene_counts(double theta_deg) {
    const double t = 2.0 * theta_deg * std::numbers::pi / 180.0;
    return 0.5 * (kS0 + kS1 * std::cos(t) + kS2 * std::sin(t));
}

BosonCoreConfig core_config() {
    BosonCoreConfig c;
    c.frame_rate_hz = 60.0;
    c.ffc_threshold_k = 0.5;
    c.ffc_duration_s = 0.5;
    c.ffc_step_std_counts = 40.0;
    c.ffc_pixel_std_counts = 3.0;
    c.seed = 11;
    return c;
}

SimulatedStageOptions stage_options() {
    SimulatedStageOptions o;
    o.deg_per_s = 720.0;  // an Elliptec-like rotation mount
    return o;
}

struct BosonRig {
    std::shared_ptr<BosonCoreModel> core;
    std::unique_ptr<Stage> stage = make_simulated_stage("sim://", stage_options());
    std::unique_ptr<SimulatedCamera> camera;
    explicit BosonRig(const BosonCoreConfig& core_settings = core_config())
        : core(std::make_shared<BosonCoreModel>(core_settings)) {
        SimulatedCameraConfig config;
        config.name = "boson";
        config.width = kWidth;
        config.height = kHeight;
        config.frame_rate_hz = 60.0;
        config.noise_std_counts = kNoise;
        config.buffers = 64;
        auto core_ref = core;
        camera = std::make_unique<SimulatedCamera>(
            config,
            [core_ref](double angle_deg, std::vector<float>& out) {
                std::fill(out.begin(), out.end(), static_cast<float>(scene_counts(angle_deg)));
                core_ref->apply(out, Clock::now());
            },
            simulated_stage_angle_source(*stage));
    }
};

CapturePlan plan(int repeats) {
    CapturePlan p;
    p.frames_per_angle = kFrames;
    p.settle_s = 0.03;
    p.repeats = repeats;
    return p;
}

/// Steps the FPA by 0.6 K (over the core's 0.5 K auto threshold) at the 45° step's third frame of
/// cycle 1.
CaptureOptions provoking(BosonCoreModel& core, bool& done) {
    CaptureOptions o;
    o.progress_stream = nullptr;
    o.on_progress = [&core, &done](const CaptureProgress& p) {
        if (!done && p.event == CaptureProgress::Event::Frame && p.step->repeat == 0 &&
            p.step->angle_deg == 45.0 && p.frames_kept == 3) {
            core.add_fpa_step_k(0.6);
            done = true;
        }
    };
    return o;
}

struct StokesBias {
    double s1 = 0.0, s2 = 0.0;
};

/// Pixel-mean S1 − kS1 and S2 − kS2 of one repeat, from the session's records (S1 = I0 − I90, S2 =
/// I45 − I135).
StokesBias bias(const std::filesystem::path& dir, int repeat) {
    auto mean = test::polarizer_means_by_angle(dir, repeat);
    EXPECT_EQ(mean.size(), 4u);
    return {mean[0] - mean[90] - kS1, mean[45] - mean[135] - kS2};
}

/// The per-pixel noise of S1 (or S2): two means of kFrames frames of kNoise each.
double stokes_noise() { return kNoise * std::sqrt(2.0 / kFrames); }

TEST(CaptureFfc, WithoutHandlingAnAutoFfcInsideACycleBiasesS1AndS2) {
    test::TempDir tmp;
    BosonRig rig;
    bool provoked = false;
    const auto options = provoking(*rig.core, provoked);
    auto session = SessionWriter::create(
        tmp / "s", new_session_manifest(rig.camera->info(), rig.stage->info(), plan(1)));
    run_capture(*rig.camera, *rig.stage, plan(1), session, options);
    ASSERT_TRUE(provoked);
    EXPECT_EQ(rig.core->auto_ffcs_started(Clock::now()), 1);
    const StokesBias b = bias(tmp / "s", 0);
    std::printf("no FFC handling: S1 bias %+.2f, S2 bias %+.2f counts (per-pixel noise %.2f)\n",
                b.s1, b.s2, stokes_noise());
    EXPECT_GT(std::max(std::abs(b.s1), std::abs(b.s2)), 5.0 * stokes_noise());
    EXPECT_TRUE(read_session(tmp / "s").ffc_events.empty());
}

TEST(CaptureFfc, WithoutALinkAnFfcInsideACycleIsDetectedAndTheCycleTakenAgain) {
    test::TempDir tmp;
    BosonRig rig;
    bool provoked = false;
    auto options = provoking(*rig.core, provoked);
    FfcOptions ffc;  // no control link: detection in the frames only
    options.ffc = &ffc;
    auto session = SessionWriter::create(
        tmp / "s", new_session_manifest(rig.camera->info(), rig.stage->info(), plan(2)));
    const auto summary = run_capture(*rig.camera, *rig.stage, plan(2), session, options);
    ASSERT_TRUE(provoked);
    EXPECT_EQ(rig.core->auto_ffcs_started(Clock::now()), 1);
    EXPECT_EQ(summary.ffc_detected, 1);
    EXPECT_EQ(summary.ffc_scheduled, 0);
    EXPECT_EQ(summary.steps_recorded, 8u);
    const SessionManifest m = read_session(tmp / "s");
    ASSERT_EQ(m.ffc_events.size(), 1u);
    EXPECT_EQ(m.ffc_events[0].kind, FfcEvent::Kind::Detected);
    EXPECT_EQ(m.ffc_events[0].repeat, 0);
    EXPECT_NE(m.ffc_events[0].reason.find("45"), std::string::npos) << m.ffc_events[0].reason;
    for (int repeat : {0, 1}) {
        const StokesBias b = bias(tmp / "s", repeat);
        std::printf(
            "detection, cycle %d: S1 bias %+.2f, S2 bias %+.2f counts (per-pixel noise %.2f)\n",
            repeat + 1, b.s1, b.s2, stokes_noise());
        EXPECT_LT(std::abs(b.s1), stokes_noise());
        EXPECT_LT(std::abs(b.s2), stokes_noise());
    }
}

TEST(CaptureFfc,
     WithoutALinkAnOffsetStepBetweenTheFortyFiveAndNinetyStepsIsFoundFromThePreviousCycle) {
    // A short FFC that starts after the last 45° frame of cycle 2: its shutter frames fall in the
    // move and settle (never kept) and the offset steps between I45 and I90, which the closure I0 +
    // I90 − I45 − I135 cannot see (the step adds to I90 and I135 alike); the change from cycle 1,
    // unequal across angles, can.
    test::TempDir tmp;
    BosonCoreConfig config = core_config();
    config.ffc_duration_s = 0.01;
    BosonRig rig(config);
    bool provoked = false;
    CaptureOptions options;
    options.progress_stream = nullptr;
    options.on_progress = [&](const CaptureProgress& p) {
        if (!provoked && p.event == CaptureProgress::Event::Frame && p.step->repeat == 1 &&
            p.step->angle_deg == 45.0 && p.frames_kept == kFrames) {
            rig.core->add_fpa_step_k(0.6);
            provoked = true;
        }
    };
    FfcOptions ffc;
    options.ffc = &ffc;
    auto session = SessionWriter::create(
        tmp / "s", new_session_manifest(rig.camera->info(), rig.stage->info(), plan(2)));
    const auto summary = run_capture(*rig.camera, *rig.stage, plan(2), session, options);
    ASSERT_TRUE(provoked);
    EXPECT_EQ(rig.core->auto_ffcs_started(Clock::now()), 1);
    EXPECT_EQ(summary.ffc_detected, 1);
    const SessionManifest m = read_session(tmp / "s");
    ASSERT_EQ(m.ffc_events.size(), 1u);
    EXPECT_EQ(m.ffc_events[0].repeat, 1);
    EXPECT_NE(m.ffc_events[0].reason.find("changed unequally"), std::string::npos)
        << m.ffc_events[0].reason;
    const StokesBias b = bias(tmp / "s", 1);
    EXPECT_LT(std::abs(b.s1), stokes_noise());
    EXPECT_LT(std::abs(b.s2), stokes_noise());
}

TEST(CaptureFfc, WithTheLinkFfcsRunBetweenCyclesAndTheCoreNeverCorrectsInside) {
    test::TempDir tmp;
    BosonRig rig;
    test::PtyDeviceThread<BosonSimulator> link_sim(rig.core);
    auto link = open_boson_control(link_sim.path(), "boson-sim").value_or_throw();
    bool provoked = false;
    auto options = provoking(*rig.core, provoked);
    FfcOptions ffc;
    ffc.control = link.get();
    ffc.schedule = FfcOptions::Schedule::EveryCycle;
    options.ffc = &ffc;
    auto session = SessionWriter::create(
        tmp / "s", new_session_manifest(rig.camera->info(), rig.stage->info(), plan(3)));
    const auto summary = run_capture(*rig.camera, *rig.stage, plan(3), session, options);
    ASSERT_TRUE(provoked);
    EXPECT_EQ(rig.core->ffc_mode(), boson::FfcMode::Manual);
    EXPECT_EQ(rig.core->auto_ffcs_started(Clock::now()),
              0);  // the FPA step came with the core in manual mode
    EXPECT_EQ(rig.core->ffcs_started(Clock::now()), 3);
    EXPECT_EQ(summary.ffc_scheduled, 3);
    EXPECT_EQ(summary.ffc_detected, 0);
    const SessionManifest m = read_session(tmp / "s");
    ASSERT_EQ(m.ffc_events.size(), 3u);
    for (int i = 0; i < 3; ++i) {
        const FfcEvent& e = m.ffc_events[static_cast<std::size_t>(i)];
        EXPECT_EQ(e.kind, FfcEvent::Kind::Scheduled);
        EXPECT_EQ(e.repeat, i);
        ASSERT_TRUE(e.device_frame_count);
        ASSERT_TRUE(e.fpa_temperature_k);
        // Each FFC ended before its cycle's first frame: the cycle's records start after it.
        const auto first = std::find_if(m.records.begin(), m.records.end(),
                                        [&](const SessionRecord& r) { return r.repeat == i; });
        ASSERT_NE(first, m.records.end());
        EXPECT_GT(first->first_timestamp_ns, e.host_timestamp_ns + 450'000'000)
            << "cycle " << i + 1;
        if (i > 0) {
            const auto& previous_last = *(first - 1);
            EXPECT_LT(previous_last.last_timestamp_ns, e.host_timestamp_ns) << "cycle " << i + 1;
        }
    }
    EXPECT_NEAR(*m.ffc_events[2].fpa_temperature_k - *m.ffc_events[0].fpa_temperature_k, 0.6, 0.1);
    // The audit: every kept frame's id and clocks; the core's state around each step from the link.
    for (const SessionRecord& r : m.records) {
        ASSERT_TRUE(r.audit) << r.file;
        const FrameAudit& a = *r.audit;
        ASSERT_EQ(a.frame_id.size(), static_cast<std::size_t>(kFrames));
        for (std::size_t k = 1; k < a.frame_id.size(); ++k) {
            EXPECT_GT(a.frame_id[k], a.frame_id[k - 1]);
            EXPECT_GT(a.device_timestamp_ns[k], a.device_timestamp_ns[k - 1]);
        }
        EXPECT_EQ(a.host_timestamp_ns.front(), r.first_timestamp_ns);
        EXPECT_EQ(a.host_timestamp_ns.back(), r.last_timestamp_ns);
        ASSERT_TRUE(a.core_before && a.core_after) << r.file;
        EXPECT_EQ(a.core_before->ffc_mode, "manual");
        EXPECT_EQ(a.core_before->gain_mode, "high");
        // At 60 Hz the core counts at least the kept frames during the step; no FFC within it.
        EXPECT_GE(a.core_after->device_frame_count - a.core_before->device_frame_count,
                  kFrames - 1);
        EXPECT_EQ(a.core_after->last_ffc_frame_count, a.core_before->last_ffc_frame_count);
        EXPECT_EQ(a.core_before->last_ffc_frame_count,
                  *m.ffc_events[static_cast<std::size_t>(r.repeat)].device_frame_count);
    }
    for (int repeat : {0, 1, 2}) {
        const StokesBias b = bias(tmp / "s", repeat);
        std::printf("link, cycle %d: S1 bias %+.2f, S2 bias %+.2f counts (per-pixel noise %.2f)\n",
                    repeat + 1, b.s1, b.s2, stokes_noise());
        EXPECT_LT(std::abs(b.s1), stokes_noise());
        EXPECT_LT(std::abs(b.s2), stokes_noise());
    }
}

TEST(CaptureFfc, WithTheLinkAnFfcTheCoreRanInsideACycleIsSeenInItsFrameCountAndTheCycleTakenAgain) {
    // Something else made the core correct mid-cycle (another program on its port, an external FFC
    // trigger): the last-FFC frame count moved between the cycle's start and end.
    test::TempDir tmp;
    BosonRig rig;
    test::PtyDeviceThread<BosonSimulator> link_sim(rig.core);
    auto link = open_boson_control(link_sim.path(), "boson-sim").value_or_throw();
    bool provoked = false;
    CaptureOptions options;
    options.progress_stream = nullptr;
    options.on_progress = [&](const CaptureProgress& p) {
        if (!provoked && p.event == CaptureProgress::Event::Frame && p.step->repeat == 0 &&
            p.step->angle_deg == 45.0 && p.frames_kept == 3) {
            rig.core->run_ffc(Clock::now());
            provoked = true;
        }
    };
    FfcOptions ffc;
    ffc.control = link.get();
    ffc.schedule = FfcOptions::Schedule::EveryN;
    ffc.every_n_cycles = 10;  // only before the first cycle
    options.ffc = &ffc;
    auto session = SessionWriter::create(
        tmp / "s", new_session_manifest(rig.camera->info(), rig.stage->info(), plan(2)));
    const auto summary = run_capture(*rig.camera, *rig.stage, plan(2), session, options);
    ASSERT_TRUE(provoked);
    EXPECT_EQ(summary.ffc_detected, 1);
    EXPECT_EQ(summary.ffc_scheduled, 2);  // before cycle 1, and before taking it again
    const SessionManifest m = read_session(tmp / "s");
    ASSERT_EQ(m.ffc_events.size(), 3u);
    EXPECT_EQ(m.ffc_events[0].kind, FfcEvent::Kind::Scheduled);
    EXPECT_EQ(m.ffc_events[1].kind, FfcEvent::Kind::Detected);
    EXPECT_NE(m.ffc_events[1].reason.find("last-FFC frame count moved"), std::string::npos)
        << m.ffc_events[1].reason;
    EXPECT_EQ(m.ffc_events[2].kind, FfcEvent::Kind::Scheduled);
    EXPECT_EQ(m.ffc_events[2].repeat, 0);
    for (int repeat : {0, 1}) {
        const StokesBias b = bias(tmp / "s", repeat);
        EXPECT_LT(std::abs(b.s1), stokes_noise());
        EXPECT_LT(std::abs(b.s2), stokes_noise());
    }
}

TEST(CaptureFfc, WithTheLinkTheFpaScheduleRunsAnFfcOnlyWhenTheFpaMoved) {
    test::TempDir tmp;
    BosonRig rig;
    test::PtyDeviceThread<BosonSimulator> link_sim(rig.core);
    auto link = open_boson_control(link_sim.path(), "boson-sim").value_or_throw();
    bool provoked = false;
    auto options = provoking(*rig.core, provoked);
    FfcOptions ffc;
    ffc.control = link.get();
    ffc.schedule = FfcOptions::Schedule::FpaDelta;
    ffc.fpa_delta_k = 0.3;
    options.ffc = &ffc;
    auto session = SessionWriter::create(
        tmp / "s", new_session_manifest(rig.camera->info(), rig.stage->info(), plan(3)));
    const auto summary = run_capture(*rig.camera, *rig.stage, plan(3), session, options);
    ASSERT_TRUE(provoked);
    // Cycle 1 (no reference yet) and cycle 2 (the FPA stepped 0.6 K during cycle 1); not cycle 3.
    EXPECT_EQ(summary.ffc_scheduled, 2);
    const SessionManifest m = read_session(tmp / "s");
    ASSERT_EQ(m.ffc_events.size(), 2u);
    EXPECT_EQ(m.ffc_events[0].repeat, 0);
    EXPECT_EQ(m.ffc_events[1].repeat, 1);
    EXPECT_NE(m.ffc_events[1].reason.find("FPA moved +0.6"), std::string::npos)
        << m.ffc_events[1].reason;
}

TEST(CaptureFfc, ACoreThatStopsAnsweringFailsTheStepByName) {
    test::TempDir tmp;
    BosonRig rig;
    BosonSimulatorOptions faulty;
    faulty.fault = BosonSimFault::Silent;
    faulty.fault_on_command = 2;  // open_boson_control's serial number passes, then silence
    test::PtyDeviceThread<BosonSimulator> link_sim(rig.core, faulty);
    BosonControlOptions driver;
    driver.reply_timeout = std::chrono::milliseconds(100);
    auto link = open_boson_control(link_sim.path(), "boson-sim", driver).value_or_throw();
    CaptureOptions options;
    options.progress_stream = nullptr;
    FfcOptions ffc;
    ffc.control = link.get();
    options.ffc = &ffc;
    auto session = SessionWriter::create(
        tmp / "s", new_session_manifest(rig.camera->info(), rig.stage->info(), plan(1)));
    try {
        run_capture(*rig.camera, *rig.stage, plan(1), session, options);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("camera control link"), std::string::npos) << what;
        EXPECT_NE(what.find("BOSON_SETFFCMODE"), std::string::npos) << what;
        EXPECT_NE(what.find("stopped answering"), std::string::npos) << what;
    }
}

}  // namespace
}  // namespace tirpol::acquisition
