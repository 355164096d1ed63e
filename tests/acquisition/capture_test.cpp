// The capture loop on a simulated camera that sees a linearly polarized scene through the polarizer
// the simulated stage turns (Malus's law): the recorded means reproduce the scene's Stokes vector
// (S1 = I0 − I90, S2 = I45 − I135, paper eqs 14–16), a device fault keeps what was recorded, and
// resuming completes the session with nothing lost or duplicated.

#include "tirpol/acquisition/capture.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <numbers>
#include <set>
#include <thread>
#include <utility>

#include "test_support.h"
#include "tirpol/acquisition/internal/sim_stage.h"
#include "tirpol/acquisition/sim/simulated_camera.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"

namespace tirpol::acquisition {
namespace {

using ::testing::HasSubstr;

// Scene: unpolarized part U plus a linearly polarized part P at angle psi; an ideal polarizer at θ
// passes U/2 + P cos²(θ − psi) (Malus).
constexpr double kUnpolarized = 4000.0, kPolarized = 1000.0, kPsiDeg = 30.0;

double malus_counts(double theta_deg) {
    const double d = (theta_deg - kPsiDeg) * std::numbers::pi / 180.0;
    return kUnpolarized / 2.0 + kPolarized * std::cos(d) * std::cos(d);
}

/// A free-running simulated camera looking through the polarizer of a simulated stage: each frame
/// shows the mount where it physically is when the frame is exposed, also mid-move.
struct Rig {
    std::unique_ptr<Stage> stage;
    std::unique_ptr<SimulatedCamera> camera;
    explicit Rig(SimulatedStageOptions stage_options = {}, double noise = 0.0, double fps = 500.0,
                 int buffers = 16) {
        stage = make_simulated_stage("sim://", stage_options);
        SimulatedCameraConfig config;
        config.width = 6;
        config.height = 4;
        config.noise_std_counts = noise;
        config.seed = 7;
        config.fpa_temperature_k = 308.0;
        config.frame_rate_hz = fps;
        config.buffers = buffers;
        camera = std::make_unique<SimulatedCamera>(
            config,
            [](double angle, std::vector<float>& out) {
                std::fill(out.begin(), out.end(), static_cast<float>(malus_counts(angle)));
            },
            simulated_stage_angle_source(*stage));
    }
};

CapturePlan small_plan() {
    CapturePlan plan = CapturePlan::parse(ConfigNode::parse(R"(
frames_per_angle: 8
settle_s: 0
repeats: 2
references:
  - kind: blackbody
    temperatures_c: [20, 40]
    frames: 4
  - kind: shutter
    frames: 3
metadata: {site: roof, targets: [panel A, panel B], air_temperature_c: 4.5}
)",
                                                            "plan.yaml"));
    return plan;
}

SessionWriter new_session(const std::filesystem::path& dir, Rig& rig, const CapturePlan& plan) {
    return SessionWriter::create(dir,
                                 new_session_manifest(rig.camera->info(), rig.stage->info(), plan));
}

/// The free-running tests' rig: the stage turns at 180°/s (45° in 0.25 s) while the camera
/// free-runs at 200 Hz into a 64-frame queue, which therefore holds frames of the whole move when a
/// step starts grabbing; noise-free Malus counts.
Rig slow_stage_rig() {
    SimulatedStageOptions slow;
    slow.deg_per_s = 180.0;
    return Rig(slow, 0.0, 200.0, 64);
}

/// Captures 0/45/90/135° with `rig`, 8 frames per angle after a 0.05 s settle, into a session at
/// `dir`.
CaptureSummary capture_after_slow_moves(Rig& rig, const std::filesystem::path& dir) {
    CapturePlan plan;
    plan.frames_per_angle = 8;
    plan.settle_s = 0.05;
    auto session = new_session(dir, rig, plan);
    CaptureOptions options;
    options.progress_stream = nullptr;
    return run_capture(*rig.camera, *rig.stage, plan, session, options);
}

/// Every pixel of the 4 records in the session at `dir` is the Malus counts of its angle within 0.5
/// (integers): a single frame from a move (up to 45° off) would move an 8-frame mean by tens of
/// counts.
void expect_only_frames_exposed_after_the_settle(const std::filesystem::path& dir) {
    const SessionManifest m = read_session(dir);
    ASSERT_EQ(m.records.size(), 4u);
    for (const auto& r : m.records) {
        const Image img = read_session_frame(dir, m, r);
        for (float v : img.channel("counts"))
            ASSERT_NEAR(v, malus_counts(r.angle_deg_requested), 0.5) << r.file;
    }
}

TEST(CapturePlan, ExpandsReferencesThenRepeatsOfTheAngles) {
    const auto steps = plan_steps(small_plan());
    ASSERT_EQ(steps.size(), 3u + 8u);
    EXPECT_EQ(steps[0].kind, RecordKind::Blackbody);
    EXPECT_NEAR(*steps[1].temperature_k, 313.15, 1e-9);
    EXPECT_EQ(steps[2].kind, RecordKind::Shutter);
    EXPECT_FALSE(steps[2].temperature_k);
    EXPECT_EQ(steps[3].file, "frames/s003_pol_000.000deg_r0.exr");
    EXPECT_EQ(steps[10].file, "frames/s010_pol_135.000deg_r1.exr");
    std::set<std::string> files;
    for (const auto& s : steps) files.insert(s.file);
    EXPECT_EQ(files.size(), steps.size());
    EXPECT_EQ(CapturePlan().angles_deg, (std::vector<double>{0, 45, 90, 135}));  // the default set
}

TEST(CapturePlan, BadPlansAreReportedByField) {
    auto error_of = [](const char* yaml) {
        try {
            CapturePlan::parse(ConfigNode::parse(yaml, "plan.yaml"));
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_THAT(error_of("frames_per_angel: 4"), HasSubstr("frames_per_angel"));
    EXPECT_THAT(error_of("frames_per_angle: 0"), HasSubstr("expected an integer ≥ 1"));
    EXPECT_THAT(error_of("angles_deg: [0, 45, 45.0]"), HasSubstr("listed twice"));
    EXPECT_THAT(error_of("references: [{kind: blackbody, frames: 3}]"),
                HasSubstr("needs temperatures_k"));
    EXPECT_THAT(error_of("references: [{kind: polarizer}]"),
                HasSubstr("expected blackbody or shutter"));
    EXPECT_THAT(error_of("settle_s: -1"), HasSubstr("settle_s"));
}

TEST(Capture, RecordsEveryStepAndTheMeansGiveTheScenesStokesVector) {
    test::TempDir tmp;
    Rig rig({}, 5.0);
    const CapturePlan plan = small_plan();
    auto session = new_session(tmp / "s", rig, plan);
    std::vector<std::string> prompts;
    CaptureOptions options;
    options.progress_stream = nullptr;
    options.prompt = [&](const std::string& text) {
        prompts.push_back(text);
        return true;
    };
    const auto summary = run_capture(*rig.camera, *rig.stage, plan, session, options);
    EXPECT_EQ(summary.steps_recorded, 11u);
    EXPECT_EQ(summary.frames, 4u * 2 + 3 + 8u * 8);
    ASSERT_EQ(prompts.size(), 3u);  // one per reference step
    EXPECT_THAT(prompts[1], HasSubstr("313.15 K"));

    const SessionManifest m = read_session(tmp / "s");
    ASSERT_TRUE(m.complete);
    ASSERT_EQ(m.records.size(), 11u);
    EXPECT_EQ(m.metadata.at("targets")[1], "panel B");
    EXPECT_EQ(m.metadata.at("air_temperature_c"), 4.5);
    std::map<std::pair<double, int>, double> mean;
    for (const auto& r : m.records) {
        EXPECT_EQ(*r.fpa_temperature_k, 308.0);
        EXPECT_LE(r.first_timestamp_ns, r.last_timestamp_ns);
        EXPECT_NEAR(r.angle_deg_measured, r.angle_deg_requested, 1e-5);
        if (r.kind != RecordKind::Polarizer) continue;
        EXPECT_EQ(r.frames, 8);
        const Image img = read_session_frame(tmp / "s", m, r);
        double sum = 0, std_sum = 0;
        for (float v : img.channel("counts")) sum += v;
        for (float v : img.channel("counts_std")) std_sum += v;
        mean[{r.angle_deg_requested, r.repeat}] = sum / static_cast<double>(img.pixel_count());
        // The per-pixel standard deviation estimates the camera's temporal noise (5 counts).
        EXPECT_NEAR(std_sum / static_cast<double>(img.pixel_count()), 5.0, 1.5);
    }
    for (int r = 0; r < 2; ++r) {
        // 8 frames × 24 pixels of σ = 5 noise: the mean is good to ~0.4 counts.
        for (double a : {0.0, 45.0, 90.0, 135.0})
            EXPECT_NEAR((mean[{a, r}]), malus_counts(a), 2.0) << a;
        const double s0 = mean[{0.0, r}] + mean[{90.0, r}];
        const double s1 = mean[{0.0, r}] - mean[{90.0, r}];
        const double s2 = mean[{45.0, r}] - mean[{135.0, r}];
        EXPECT_NEAR(s0, kUnpolarized + kPolarized, 4.0);
        EXPECT_NEAR(std::hypot(s1, s2), kPolarized, 4.0);  // DoLP × S0
        EXPECT_NEAR(0.5 * std::atan2(s2, s1) * 180.0 / std::numbers::pi, kPsiDeg, 0.3);  // AoP
    }
}

TEST(Capture, FreeRunningCameraDuringSlowMovesGivesOnlyFramesExposedAfterTheSettle) {
    // Each step's queue holds frames of the whole 45° move (slow_stage_rig): only those exposed
    // after the settle may be averaged.
    test::TempDir tmp;
    Rig rig = slow_stage_rig();
    const auto summary = capture_after_slow_moves(rig, tmp / "s");
    EXPECT_GT(summary.stale_discarded, 0u);
    expect_only_frames_exposed_after_the_settle(tmp / "s");

    const SessionManifest m = read_session(tmp / "s");
    EXPECT_EQ(m.schema_version, kSessionSchemaVersion);
    ASSERT_EQ(m.records.size(), 4u);
    // What the camera delivered, measured: at most its 200 Hz (less when the loaded machine slows
    // it).
    ASSERT_TRUE(m.camera.frame_rate_hz);
    EXPECT_GT(*m.camera.frame_rate_hz, 20.0);
    EXPECT_LT(*m.camera.frame_rate_hz, 210.0);
    std::int64_t previous_last = 0;
    for (const auto& r : m.records) {
        ASSERT_TRUE(r.timing) << r.file;
        const StepTiming& t = *r.timing;
        EXPECT_LE(previous_last, t.move_start_ns);
        EXPECT_LE(t.move_start_ns, t.move_end_ns);
        EXPECT_EQ(t.settle_end_ns, t.move_end_ns + 50'000'000);
        EXPECT_GE(t.exposure_window_ns,
                  7'500'000);  // 1.5 periods at 200 Hz, more if the loaded machine slows the camera
        EXPECT_GE(r.first_timestamp_ns - t.exposure_window_ns, t.settle_end_ns) << r.file;
        EXPECT_NEAR(t.angle_deg_before_frames, r.angle_deg_requested, 1e-5);
        EXPECT_NEAR(t.angle_deg_after_frames, r.angle_deg_requested, 1e-5);
        previous_last = r.last_timestamp_ns;
    }
    // The 45° moves took 0.25 s at up to 200 Hz: the frames of each were queued and thrown away (≈
    // 50 on an idle machine; a loaded one slows the simulated sensor).
    for (std::size_t i = 1; i < 4; ++i)
        EXPECT_GE(m.records[i].timing->stale_frames_discarded, 10) << m.records[i].file;
}

TEST(Capture, AFrameHeldUpOnTheCamerasThreadDuringAMoveIsNotAveraged) {
    // A loaded machine holds the camera's thread up for 0.4 s right after it read the polarizer
    // mid-move (the first mid-move frame of each move). The move (45° at 180°/s, 0.25 s) and the
    // 0.05 s settle end before that frame leaves the camera, but its exposure ended mid-move: its
    // stamp must say so, or the gate takes it for a frame exposed after the settle and one frame up
    // to 45° off moves the 8-frame mean by tens of counts (noise-free Malus counts: within 0.5).
    test::TempDir tmp;
    Rig rig = slow_stage_rig();
    SimulatedCameraConfig config;
    config.width = 6;
    config.height = 4;
    config.frame_rate_hz = 200.0;
    config.buffers = 64;
    std::atomic<int> held_frames{0};
    bool held_this_move = false;  // the camera's thread alone touches it
    rig.camera = std::make_unique<SimulatedCamera>(
        config,
        [&](double angle, std::vector<float>& out) {
            const bool mid_move = std::abs(std::remainder(angle, 45.0)) > 0.5;
            if (mid_move && !held_this_move) {
                held_this_move = true;
                ++held_frames;
                std::this_thread::sleep_for(std::chrono::milliseconds(400));
            }
            if (!mid_move) held_this_move = false;
            std::fill(out.begin(), out.end(), static_cast<float>(malus_counts(angle)));
        },
        simulated_stage_angle_source(*rig.stage));
    capture_after_slow_moves(rig, tmp / "s");
    EXPECT_GE(held_frames.load(), 3);  // the three 45° moves each had their held-up frame
    expect_only_frames_exposed_after_the_settle(tmp / "s");
}

/// Test double: a stage that creeps 0.1° per read-back once it has arrived, as a mount losing its
/// hold would.
class CreepingStage final : public Stage {
public:
    StageInfo info() const override { return {"creep://", "test", "creeping", "0", "0", 100.0}; }
    Status home(std::chrono::milliseconds) override { return ok_status(); }
    bool is_homed() const override { return true; }
    Status move_absolute(double angle_deg, std::chrono::milliseconds) override {
        m_angle = angle_deg;
        return ok_status();
    }
    Result<double> position_deg() override { return std::exchange(m_angle, m_angle + 0.1); }

private:
    double m_angle = 0;
};

TEST(Capture, StageThatMovesDuringTheFramesFailsTheStepAndKeepsNothingOfIt) {
    // Documented choice (docs/acquisition-stages.md): a read-back after the frames that differs
    // from the one before by more than angle_tolerance_deg is an error, not a flagged record.
    test::TempDir tmp;
    Rig rig;
    CreepingStage stage;
    CapturePlan plan;
    plan.settle_s = 0;
    plan.frames_per_angle = 2;
    auto session = SessionWriter::create(
        tmp / "s", new_session_manifest(rig.camera->info(), stage.info(), plan));
    CaptureOptions options;
    options.progress_stream = nullptr;
    EXPECT_THAT([&] { run_capture(*rig.camera, stage, plan, session, options); },
                ::testing::ThrowsMessage<Error>(AllOf(
                    HasSubstr("step 1/4"), HasSubstr("after the frames"), HasSubstr("drifted"),
                    HasSubstr("0 of 4 steps are recorded"), HasSubstr("--resume"))));
    EXPECT_TRUE(read_session(tmp / "s").records.empty());
}

TEST(Capture, TooLittleFreeSpaceIsRefusedSayingHowMuchIsNeeded) {
    test::TempDir tmp;
    const auto space = std::filesystem::space(tmp.path());
    // Enough 640×512 steps to exceed what this file system has free.
    const std::uintmax_t per_step =
        session_bytes_needed(640, 512, 1) - session_bytes_needed(640, 512, 0);
    const std::size_t steps = static_cast<std::size_t>(space.available / per_step) + 10;
    EXPECT_THAT(
        [&] { check_free_space(tmp.path(), 640, 512, steps); },
        ::testing::ThrowsMessage<Error>(AllOf(HasSubstr("MB"), HasSubstr("free"),
                                              HasSubstr(std::to_string(steps) + " steps"))));
    EXPECT_NO_THROW(check_free_space(tmp.path(), 640, 512, 1));
}

TEST(Capture, DeviceFaultKeepsRecordsAndResumeCompletesWithoutDuplicates) {
    test::TempDir tmp;
    const auto dir = tmp / "s";
    const CapturePlan plan = small_plan();
    std::string first_record_json;
    {
        SimulatedStageOptions failing;
        failing.fail_on_move = 6;  // the 6th move: step 6 of 11
        Rig rig(failing);
        auto session = new_session(dir, rig, plan);
        CaptureOptions options;
        options.progress_stream = nullptr;
        EXPECT_THAT([&] { run_capture(*rig.camera, *rig.stage, plan, session, options); },
                    ::testing::ThrowsMessage<Error>(
                        AllOf(HasSubstr("step 6/11"), HasSubstr("stage device fault"),
                              HasSubstr("5 of 11 steps are recorded"), HasSubstr("--resume"))));
        first_record_json = read_file(dir / "session.json");
    }
    SessionManifest interrupted = read_session(dir);
    EXPECT_FALSE(interrupted.complete);
    ASSERT_EQ(interrupted.records.size(), 5u);
    const std::string first_frame_bytes = read_file(dir / interrupted.records[0].file);

    Rig rig;
    auto session = SessionWriter::resume(dir);
    check_resumable(session.manifest(), rig.camera->info(), plan);
    CaptureOptions options;
    options.progress_stream = nullptr;
    const auto summary = run_capture(*rig.camera, *rig.stage, plan, session, options);
    EXPECT_EQ(summary.steps_already_recorded, 5u);
    EXPECT_EQ(summary.steps_recorded, 6u);

    const SessionManifest m = read_session(dir);
    EXPECT_TRUE(m.complete);
    ASSERT_EQ(m.records.size(), 11u);
    const auto steps = plan_steps(plan);
    for (std::size_t i = 0; i < steps.size(); ++i)
        EXPECT_EQ(m.records[i].file, steps[i].file);  // each once, in order
    for (std::size_t i = 0; i < 5; ++i)
        EXPECT_EQ(m.records[i], interrupted.records[i]);  // nothing rewritten
    EXPECT_EQ(read_file(dir / m.records[0].file), first_frame_bytes);
    std::size_t files = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir / "frames"))
        files += e.path().extension() == ".exr";
    EXPECT_EQ(files, 11u);

    // Running again on a complete session records nothing.
    EXPECT_EQ(run_capture(*rig.camera, *rig.stage, plan, session, options).steps_recorded, 0u);
}

TEST(Capture, ProgressReportsEveryKeptFrameThenItsStepInPlanOrder) {
    test::TempDir tmp;
    Rig rig;
    const CapturePlan plan = small_plan();
    auto session = new_session(tmp / "s", rig, plan);
    struct Event {
        CaptureProgress progress;
        std::string file;  // CaptureProgress::step points into run_capture's own step list
    };
    std::vector<Event> events;
    CaptureOptions options;
    options.progress_stream = nullptr;
    options.on_progress = [&](const CaptureProgress& p) { events.push_back({p, p.step->file}); };
    run_capture(*rig.camera, *rig.stage, plan, session, options);

    // Each step: frames_kept 1 … frames as Frame events, then one StepRecorded; nothing else.
    const auto steps = plan_steps(plan);
    std::size_t e = 0;
    for (const auto& step : steps) {
        for (int f = 1; f <= step.frames; ++f, ++e) {
            ASSERT_LT(e, events.size());
            EXPECT_EQ(events[e].progress.event, CaptureProgress::Event::Frame);
            EXPECT_EQ(events[e].file, step.file);
            EXPECT_EQ(events[e].progress.frames_kept, f);
            EXPECT_EQ(events[e].progress.steps_recorded, step.index);
            if (f > 1) EXPECT_GT(events[e].progress.frame_id, events[e - 1].progress.frame_id);
        }
        ASSERT_LT(e, events.size());
        EXPECT_EQ(events[e].progress.event, CaptureProgress::Event::StepRecorded);
        EXPECT_EQ(events[e].file, step.file);
        EXPECT_EQ(events[e].progress.steps_recorded, step.index + 1);
        EXPECT_EQ(events[e].progress.steps_total, steps.size());
        ++e;
    }
    EXPECT_EQ(e, events.size());
}

TEST(Capture, AThrowingProgressCallbackStopsTheCaptureAndTheSessionResumes) {
    test::TempDir tmp;
    const auto dir = tmp / "s";
    const CapturePlan plan = small_plan();
    {
        Rig rig;
        auto session = new_session(dir, rig, plan);
        CaptureOptions options;
        options.progress_stream = nullptr;
        // Stops during step 5's third frame: steps 1–4 are recorded, step 5's frames are dropped.
        options.on_progress = [](const CaptureProgress& p) {
            if (p.step->index == 4 && p.frames_kept == 3) throw std::runtime_error("enough");
        };
        EXPECT_THAT([&] { run_capture(*rig.camera, *rig.stage, plan, session, options); },
                    ::testing::ThrowsMessage<std::runtime_error>(HasSubstr("enough")));
    }
    ASSERT_EQ(read_session(dir).records.size(), 4u);
    Rig rig;
    auto session = SessionWriter::resume(dir);
    CaptureOptions options;
    options.progress_stream = nullptr;
    std::size_t first_reported = 0;
    options.on_progress = [&](const CaptureProgress& p) {
        if (first_reported == 0) first_reported = p.step->index + 1;
    };
    const auto summary = run_capture(*rig.camera, *rig.stage, plan, session, options);
    EXPECT_EQ(first_reported, 5u);
    EXPECT_EQ(summary.steps_recorded, 7u);
    EXPECT_TRUE(read_session(dir).complete);
}

TEST(Capture, ResumeRefusesADifferentPlan) {
    test::TempDir tmp;
    Rig rig;
    const CapturePlan plan = small_plan();
    { auto session = new_session(tmp / "s", rig, plan); }
    CapturePlan other = plan;
    other.frames_per_angle = 9;
    auto session = SessionWriter::resume(tmp / "s");
    EXPECT_THAT([&] { check_resumable(session.manifest(), rig.camera->info(), other); },
                ::testing::ThrowsMessage<Error>(HasSubstr("the plan differs")));
}

TEST(Capture, OperatorCanStopAtAReferencePrompt) {
    test::TempDir tmp;
    Rig rig;
    const CapturePlan plan = small_plan();
    auto session = new_session(tmp / "s", rig, plan);
    CaptureOptions options;
    options.progress_stream = nullptr;
    options.prompt = [](const std::string&) { return false; };
    EXPECT_THAT(
        [&] { run_capture(*rig.camera, *rig.stage, plan, session, options); },
        ::testing::ThrowsMessage<Error>(HasSubstr("stopped by the operator before step 1/11")));
    EXPECT_TRUE(read_session(tmp / "s").records.empty());
}

/// Test double: a stage whose encoder reads 0.3° off, as a slipping mount would.
class SlippingStage final : public Stage {
public:
    StageInfo info() const override { return {"slip://", "test", "slipping", "0", "0", 100.0}; }
    Status home(std::chrono::milliseconds) override { return ok_status(); }
    bool is_homed() const override { return true; }
    Status move_absolute(double angle_deg, std::chrono::milliseconds) override {
        m_angle = angle_deg;
        return ok_status();
    }
    Result<double> position_deg() override { return m_angle + 0.3; }

private:
    double m_angle = 0;
};

TEST(Capture, AngleReadBackOutsideToleranceStopsTheStep) {
    test::TempDir tmp;
    Rig rig;
    SlippingStage stage;
    CapturePlan plan;
    plan.settle_s = 0;
    auto session = SessionWriter::create(
        tmp / "s", new_session_manifest(rig.camera->info(), stage.info(), plan));
    CaptureOptions options;
    options.progress_stream = nullptr;
    EXPECT_THAT([&] { run_capture(*rig.camera, stage, plan, session, options); },
                ::testing::ThrowsMessage<Error>(
                    HasSubstr("reads 0.3000° after settling (moved to 0.0000°")));
}

TEST(Capture, AFailedWriteNamesTheStepWhoseFileItWas) {
    // Records are written on a thread behind the capture, so a full disk surfaces one or two steps
    // later; the message must still name the step whose file could not be written. A file-size
    // limit makes write(2) fail as a full disk does (EFBIG; SIGXFSZ ignored): the 45° frame is
    // random 16-bit texture (≥ 40 KB however compressed), the others are flat (a few hundred
    // bytes).
    test::TempDir tmp;
    auto stage = make_simulated_stage("sim://", {});
    SimulatedCameraConfig config;
    config.width = 160;
    config.height = 128;
    config.frame_rate_hz = 500.0;
    SimulatedCamera camera(
        config,
        [](double angle, std::vector<float>& out) {
            std::uint32_t state = 12345;
            for (auto& v : out) {
                state = state * 1664525u + 1013904223u;
                v = std::abs(angle - 45.0) < 1.0 ? static_cast<float>(state >> 16) : 1000.0f;
            }
        },
        simulated_stage_angle_source(*stage));
    CapturePlan plan;
    plan.settle_s = 0;
    plan.frames_per_angle = 2;
    auto session =
        SessionWriter::create(tmp / "s", new_session_manifest(camera.info(), stage->info(), plan));
    CaptureOptions options;
    options.progress_stream = nullptr;
    rlimit old{};
    ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
    auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limited = old;
    limited.rlim_cur = 16 * 1024;
    ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &limited), 0);
    std::string error;
    try {
        run_capture(camera, *stage, plan, session, options);
    } catch (const Error& e) {
        error = e.what();
    }
    ::setrlimit(RLIMIT_FSIZE, &old);
    std::signal(SIGXFSZ, old_handler);
    EXPECT_THAT(error, AllOf(HasSubstr("step 2/4 (polarizer 45°"),
                             HasSubstr("writing the session failed")));
    EXPECT_EQ(read_session(tmp / "s").records.size(), 1u);
}

}  // namespace
}  // namespace tirpol::acquisition
