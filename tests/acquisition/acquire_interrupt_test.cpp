// Ctrl-C (SIGINT) and SIGTERM during `tirpol acquire`, end to end: the real executable, a
// `tirpol-stage-sim` process speaking APT on a pseudo-terminal at a K10CR1's speed (10°/s, so a
// 45° move takes 4.5 s), and a sim:// camera. One signal during a move, a homing or a long settle
// ends the program (exit 1) with "interrupted" and the --resume hint, keeps every recorded step,
// and leaves the stage stopped where it was (MGMSG_MOT_MOVE_STOP was sent: a stage not told to stop
// would carry on to its target). The session resumes to completion.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <nlohmann/json.hpp>
#include <thread>

#include "acquire_cli.h"
#include "child_process.h"
#include "test_support.h"
#include "tirpol/acquisition/stage.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/session.h"

namespace tirpol::acquisition {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;

/// No run here may need longer than this; a hang fails the test instead of blocking CTest.
constexpr auto kBound = 60s;

std::unique_ptr<test::ChildProcess> start_stage_sim(const std::filesystem::path& dir,
                                                    const char* deg_per_s) {
    auto sim = std::make_unique<test::ChildProcess>(
        std::vector<std::string>{TIRPOL_STAGE_SIM_PATH, "--protocol", "apt", "--link",
                                 (dir / "stage").string(), "--move-deg-per-s", deg_per_s},
        dir / "stage-sim.log");
    for (int i = 0; i < 500 && !std::filesystem::exists(dir / "stage"); ++i)
        std::this_thread::sleep_for(10ms);
    return sim;
}

std::unique_ptr<test::ChildProcess> start_acquire(const std::filesystem::path& dir, const char* log,
                                                  bool resume = false) {
    return std::make_unique<test::ChildProcess>(
        test::acquire_cli_args(dir, dir / "plan.yaml",
                               "sim://uniform?width=16&height=12&counts=1000&noise=2&fps=100",
                               resume),
        dir / log);
}

std::size_t records_in(const std::filesystem::path& session) {
    try {
        return nlohmann::json::parse(read_file(session / "session.json")).at("records").size();
    } catch (const std::exception&) {
        return 0;  // not created yet
    }
}

/// Waits until the session exists and holds at least `records` records.
void wait_for_records(const std::filesystem::path& session, std::size_t records) {
    const auto end = std::chrono::steady_clock::now() + kBound;
    while (std::chrono::steady_clock::now() < end &&
           !(std::filesystem::exists(session / "session.json") && records_in(session) >= records))
        std::this_thread::sleep_for(10ms);
}

/// The stage's angle read twice, 300 ms apart, by a new connection after tirpol has exited.
std::pair<double, double> stage_angle_twice(const std::filesystem::path& dir) {
    auto stage = open_stage("thorlabs-apt://" + (dir / "stage").string()).value_or_throw();
    const double first = stage->position_deg().value_or_throw();
    std::this_thread::sleep_for(300ms);
    return {first, stage->position_deg().value_or_throw()};
}

TEST(AcquireInterrupt, CtrlCDuringAMoveStopsTheStageKeepsTheSessionAndResumes) {
    test::TempDir tmp;
    test::write_text(tmp / "plan.yaml",
                     "angles_deg: [0, 45, 90]\nframes_per_angle: 3\nsettle_s: 0.01\n");
    auto sim = start_stage_sim(tmp.path(), "10");
    {
        auto acquire = start_acquire(tmp.path(), "first.log");
        wait_for_records(tmp / "session", 1);  // homed (3.75 s) and recorded 0°
        ASSERT_EQ(records_in(tmp / "session"), 1u) << read_file(tmp / "first.log");
        std::this_thread::sleep_for(1500ms);  // 15° into the 4.5 s move to 45°
        acquire->signal(SIGINT);
        const auto code = acquire->wait_for(kBound);
        ASSERT_TRUE(code) << "tirpol acquire did not exit after SIGINT";
        EXPECT_EQ(*code, 1);
        const std::string log = read_file(tmp / "first.log");
        EXPECT_THAT(log, HasSubstr("interrupted during the move (step 2/3, polarizer 45°)"));
        EXPECT_THAT(log, HasSubstr("1 of 3 steps are recorded"));
        EXPECT_THAT(log, HasSubstr("--resume"));
    }
    const auto [first, later] = stage_angle_twice(tmp.path());
    EXPECT_GT(first, 1.0) << "the move had not started";
    EXPECT_LT(first, 44.0) << "the stage was not stopped: it went on to 45°";
    EXPECT_NEAR(later, first, 1e-6) << "the stage kept moving after tirpol exited";
    const SessionManifest kept = read_session(tmp / "session");
    EXPECT_FALSE(kept.complete);
    ASSERT_EQ(kept.records.size(), 1u);

    auto resume = start_acquire(tmp.path(), "resume.log", true);
    const auto code = resume->wait_for(kBound);
    ASSERT_TRUE(code);
    ASSERT_EQ(*code, 0) << read_file(tmp / "resume.log");
    const SessionManifest done = read_session(tmp / "session");
    EXPECT_TRUE(done.complete);
    ASSERT_EQ(done.records.size(), 3u);
    EXPECT_EQ(done.records[0], kept.records[0]);
    EXPECT_NEAR(done.records[1].angle_deg_measured, 45.0, 0.05);
}

TEST(AcquireInterrupt, SigtermDuringHomingStopsTheHoming) {
    test::TempDir tmp;
    test::write_text(tmp / "plan.yaml", "frames_per_angle: 2\nsettle_s: 0.01\n");
    auto sim = start_stage_sim(tmp.path(), "10");  // homing from 37.5° takes 3.75 s
    auto acquire = start_acquire(tmp.path(), "acquire.log");
    wait_for_records(tmp / "session", 0);
    std::this_thread::sleep_for(1s);
    acquire->signal(SIGTERM);
    const auto code = acquire->wait_for(kBound);
    ASSERT_TRUE(code);
    EXPECT_EQ(*code, 1);
    const std::string log = read_file(tmp / "acquire.log");
    EXPECT_THAT(log, HasSubstr("interrupted during homing"));
    EXPECT_THAT(log, HasSubstr("--resume"));
    const auto [first, later] = stage_angle_twice(tmp.path());
    EXPECT_GT(first, 1.0) << "the homing was not stopped: it reached 0°";
    EXPECT_LT(first, 37.0) << "the homing had not started";
    EXPECT_NEAR(later, first, 1e-6);
    EXPECT_FALSE(read_session(tmp / "session").complete);
}

TEST(AcquireInterrupt, OneSignalEndsALongSettle) {
    test::TempDir tmp;
    test::write_text(tmp / "plan.yaml", "frames_per_angle: 2\nsettle_s: 3000\n");
    auto sim = start_stage_sim(tmp.path(), "2000");
    auto acquire = start_acquire(tmp.path(), "acquire.log");
    wait_for_records(tmp / "session", 0);
    std::this_thread::sleep_for(500ms);  // homed and moved in a few ms; now settling for 50 minutes
    acquire->signal(SIGTERM);
    const auto code = acquire->wait_for(kBound);
    ASSERT_TRUE(code) << "a single SIGTERM did not end a settle_s wait";
    EXPECT_EQ(*code, 1);
    const std::string log = read_file(tmp / "acquire.log");
    EXPECT_THAT(log, HasSubstr("interrupted while the stage settled (step 1/4, polarizer 0°)"));
    EXPECT_THAT(log, HasSubstr("--resume"));
}

}  // namespace
}  // namespace tirpol::acquisition
