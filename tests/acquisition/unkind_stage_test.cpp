// Stages as they really are: backlash, lost steps and encoder error in the stage simulator, driven
// over a pseudo-terminal through the real drivers and byte protocols (Thorlabs APT binary, Elliptec
// ASCII), with moves that take time. What the camera sees is the simulator's physical mount angle;
// what the host sees is the protocol's read-back (a K10CR1's step counter, an ELL14's encoder).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "child_process.h"
#include "stage_simulator_thread.h"
#include "test_support.h"
#include "tirpol/acquisition/capture.h"
#include "tirpol/acquisition/internal/angles.h"
#include "tirpol/acquisition/sim/simulated_camera.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/config.h"
#include "tirpol/core/error.h"

namespace tirpol::acquisition {
namespace {

using ::testing::HasSubstr;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

constexpr double kBacklashDeg = 0.8;

StageSimulatorOptions apt_options() {
    StageSimulatorOptions o;
    o.protocol = SimProtocol::Apt;
    o.deg_per_s = 1500.0;  // a real delay per move (a 45° move takes 30 ms), short enough for CI
    o.start_deg = 20.0;
    return o;
}

double mount_error_deg(const test::StageSimulatorThread& sim, double commanded_deg) {
    return angle_difference_deg(sim.simulator().physical_angle_deg(Clock::now()), commanded_deg);
}

TEST(UnkindStage, MovesTakeTheTimeTheirTravelNeedsAtTheSetSpeed) {
    StageSimulatorOptions o = apt_options();
    o.deg_per_s = 300.0;
    test::StageSimulatorThread sim(o);
    auto stage = open_stage("thorlabs-apt://" + sim.path()).value_or_throw();
    stage->home(10s).value_or_throw();
    const auto start = Clock::now();
    stage->move_absolute(90.0, 10s).value_or_throw();
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    EXPECT_GE(seconds, 90.0 / 300.0);  // 0.3 s of travel: the completion never comes earlier
}

TEST(UnkindStage, WithBacklashTwoDirectionMovesMissByTheBacklashAndTheReadBackCannotTell) {
    StageSimulatorOptions o = apt_options();
    o.backlash_deg = kBacklashDeg;
    test::StageSimulatorThread sim(o);
    auto stage = open_stage("thorlabs-apt://" + sim.path()).value_or_throw();
    stage->home(10s).value_or_throw();
    double worst_deg = 0.0;
    for (double target : {45.0, 90.0, 135.0, 0.0, 45.0}) {  // up, up, up, down, up
        stage->move_absolute(target, 10s).value_or_throw();
        worst_deg = std::max(worst_deg, std::abs(mount_error_deg(sim, target)));
        // The K10CR1 reports its step counter: exactly the commanded angle.
        EXPECT_NEAR(stage->position_deg().value_or_throw(), target, 1e-3);
    }
    EXPECT_NEAR(worst_deg, kBacklashDeg, 1e-3);
}

TEST(UnkindStage, OneDirectionApproachArrivesWhereCommandedDespiteBacklash) {
    StageSimulatorOptions o = apt_options();
    o.backlash_deg = kBacklashDeg;
    test::StageSimulatorThread sim(o);
    auto stage = open_stage("thorlabs-apt://" + sim.path()).value_or_throw();
    stage->home(10s).value_or_throw();
    for (double target : {45.0, 90.0, 135.0, 0.0, 45.0}) {
        stage->move_absolute(target + 2.0, 10s)
            .value_or_throw();  // overshoot by more than the play
        stage->move_absolute(target, 10s).value_or_throw();
        EXPECT_NEAR(mount_error_deg(sim, target), 0.0, 1e-3) << target << "°";
    }
}

TEST(UnkindStage, AnElliptecReportsItsEncoderSoLostStepsAndEncoderErrorShowInTheReadBack) {
    StageSimulatorOptions o = apt_options();
    o.protocol = SimProtocol::Elliptec;
    o.lost_step_probability = 1.0;
    o.lost_step_deg = 0.5;
    o.encoder_error_deg = 0.02;
    test::StageSimulatorThread sim(o);
    auto stage = open_stage("elliptec://" + sim.path() + "?address=0").value_or_throw();
    stage->home(10s).value_or_throw();
    stage->move_absolute(90.0, 10s).value_or_throw();
    // The mount fell 0.5° short; the encoder reads it with its once-per-turn error
    // (0.02·sin 89.5°).
    const double read_deg = stage->position_deg().value_or_throw();
    EXPECT_NEAR(sim.simulator().physical_angle_deg(Clock::now()), 89.5, 1e-9);
    EXPECT_NEAR(read_deg, 89.5 + 0.02 * std::sin(89.5 * 3.14159265358979 / 180.0), 0.01);
}

// --- the capture loop on the APT simulator, a simulated camera looking through its mount ---------

/// Where the mount physically is during each kept frame, relative to the step's angle.
struct CaptureRun {
    double worst_polarizer_error_deg = 0.0;
    CaptureSummary summary;
};

CaptureRun capture_on(test::StageSimulatorThread& sim, const std::string& plan_yaml,
                      const std::filesystem::path& dir) {
    auto stage = open_stage("thorlabs-apt://" + sim.path()).value_or_throw();
    SimulatedCameraConfig config;
    config.width = 4;
    config.height = 2;
    config.frame_rate_hz = 400.0;
    SimulatedCamera camera(
        config, [](double, std::vector<float>& out) { std::fill(out.begin(), out.end(), 1000.f); },
        [&sim] { return sim.simulator().physical_angle_deg(Clock::now()); });
    const CapturePlan plan = CapturePlan::parse(ConfigNode::parse(plan_yaml, "plan.yaml"));
    auto session =
        SessionWriter::create(dir, new_session_manifest(camera.info(), stage->info(), plan));
    CaptureRun run;
    CaptureOptions options;
    options.progress_stream = nullptr;
    options.on_progress = [&](const CaptureProgress& p) {
        if (p.event != CaptureProgress::Event::Frame || p.step->kind != RecordKind::Polarizer)
            return;
        run.worst_polarizer_error_deg = std::max(run.worst_polarizer_error_deg,
                                                 std::abs(mount_error_deg(sim, p.step->angle_deg)));
    };
    run.summary = run_capture(camera, *stage, plan, session, options);
    return run;
}

constexpr const char* kPlan = R"(
frames_per_angle: 2
settle_s: 0
repeats: 2
)";

TEST(UnkindStageCapture, WithBacklashDirectMovesBiasThePolarizerAngleByTheBacklash) {
    test::TempDir tmp;
    StageSimulatorOptions o = apt_options();
    o.backlash_deg = kBacklashDeg;
    test::StageSimulatorThread sim(o);
    const auto run = capture_on(sim, kPlan, tmp / "s");
    EXPECT_EQ(run.summary.steps_recorded, 8u);  // the read-back passed every tolerance check
    EXPECT_NEAR(run.worst_polarizer_error_deg, kBacklashDeg, 1e-3);
}

TEST(UnkindStageCapture, WithBacklashTheOneDirectionApproachPutsThePolarizerWhereAsked) {
    test::TempDir tmp;
    StageSimulatorOptions o = apt_options();
    o.backlash_deg = kBacklashDeg;
    test::StageSimulatorThread sim(o);
    const auto run = capture_on(sim, std::string(kPlan) + "approach_overshoot_deg: 2\n", tmp / "s");
    EXPECT_EQ(run.summary.steps_recorded, 8u);
    EXPECT_LT(run.worst_polarizer_error_deg, 1e-3);
}

TEST(UnkindStageCapture, LostStepsInvisibleToTheStepCounterAreCaughtByTheHomeCheck) {
    test::TempDir tmp;
    StageSimulatorOptions o = apt_options();
    o.lost_step_probability = 0.3;
    o.lost_step_deg = 1.0;  // four home-sensor widths (±0.25°)
    o.seed = 11;
    test::StageSimulatorThread sim(o);
    try {
        capture_on(sim, std::string(kPlan) + "home_check_every: 1\n", tmp / "s");
        FAIL() << "lost steps went unnoticed (" << sim.simulator().slipped_moves()
               << " moves slipped)";
    } catch (const Error& e) {
        EXPECT_GT(sim.simulator().slipped_moves(), 0);
        EXPECT_THAT(e.what(), HasSubstr("lost steps"));
        EXPECT_THAT(e.what(), HasSubstr("was homed again"));
    }
    // The failed check is in the session (schema v6) with the steps it puts in doubt: those since
    // the last passing check, all of them when none passed.
    const SessionManifest m = read_session(tmp / "s");
    ASSERT_FALSE(m.home_checks.empty());
    const HomeCheck& failed = m.home_checks.back();
    EXPECT_FALSE(failed.passed);
    int last_good_before = 0;
    for (std::size_t i = 0; i + 1 < m.home_checks.size(); ++i) {
        EXPECT_TRUE(m.home_checks[i].passed);  // the capture stops at the first failure
        last_good_before = m.home_checks[i].before_step;
    }
    EXPECT_EQ(failed.steps_since_last_good, failed.before_step - last_good_before);
    EXPECT_GT(failed.host_timestamp_ns, 0);
    // Homed again: the mount is back where the counter says.
    EXPECT_NEAR(sim.simulator().physical_angle_deg(Clock::now() + 10s), 0.0, 1e-9);
}

TEST(UnkindStageCapture, WithoutLostStepsTheHomeChecksPass) {
    test::TempDir tmp;
    StageSimulatorOptions o = apt_options();
    o.backlash_deg = kBacklashDeg;  // the approach from above keeps the play out of the check too
    test::StageSimulatorThread sim(o);
    const auto run = capture_on(
        sim, std::string(kPlan) + "home_check_every: 1\napproach_overshoot_deg: 2\n", tmp / "s");
    EXPECT_EQ(run.summary.steps_recorded, 8u);
    EXPECT_EQ(run.summary.home_checks, 2);  // before cycle 2 and after the last
    // Each check in the session: when, passed, the steps it vouches for.
    const SessionManifest m = read_session(tmp / "s");
    ASSERT_EQ(m.home_checks.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
        EXPECT_TRUE(m.home_checks[i].passed);
        EXPECT_EQ(m.home_checks[i].before_step, 4 * static_cast<int>(i + 1));
        EXPECT_EQ(m.home_checks[i].steps_since_last_good, 4);
    }
    EXPECT_LT(m.home_checks[0].host_timestamp_ns, m.home_checks[1].host_timestamp_ns);
    // `tirpol info SESSION` shows them.
    test::ChildProcess info({TIRPOL_CLI_PATH, "info", (tmp / "s").string()}, tmp / "info.log");
    ASSERT_EQ(info.wait_for(60s).value_or(-1), 0) << read_file(tmp / "info.log");
    const std::string out = read_file(tmp / "info.log");
    EXPECT_THAT(out, HasSubstr("schema v6, complete"));
    EXPECT_THAT(out, HasSubstr("lost-step checks at the home sensor: 2 passed, 0 failed"));
    EXPECT_THAT(out, HasSubstr("before step 5: passed, 4 steps since the last good check"));
    EXPECT_THAT(out, HasSubstr("before step 9: passed, 4 steps since the last good check"));
}

TEST(UnkindStageCapture, AnApproachPastAFullTurnIsRefusedByThePlan) {
    try {
        CapturePlan::parse(
            ConfigNode::parse("angles_deg: [0, 359]\napproach_overshoot_deg: 2\n", "plan.yaml"));
        FAIL() << "accepted";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("approach_overshoot_deg"));
        EXPECT_THAT(e.what(), HasSubstr("361"));
    }
}

}  // namespace
}  // namespace tirpol::acquisition
