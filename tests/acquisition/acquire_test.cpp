// End to end: the real `tirpol acquire` executable with a sim:// camera and a `tirpol-stage-sim`
// process speaking the APT protocol on a pseudo-terminal. A full run gives a valid complete
// session; a run killed with SIGKILL mid-session and resumed gives a complete session with every
// step exactly once and every record written before the kill unchanged.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <set>
#include <thread>

#include "acquire_cli.h"
#include "child_process.h"
#include "test_support.h"
#include "tirpol/acquisition/capture_plan.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/session.h"

namespace tirpol::acquisition {
namespace {

using namespace std::chrono_literals;

using Child = test::ChildProcess;

/// `tirpol-stage-sim --protocol apt` linked at DIR/stage, waiting until the link exists.
std::unique_ptr<Child> start_stage_sim(const std::filesystem::path& dir, const char* speed) {
    auto sim = std::make_unique<Child>(
        std::vector<std::string>{TIRPOL_STAGE_SIM_PATH, "--protocol", "apt", "--link",
                                 (dir / "stage").string(), "--move-deg-per-s", speed},
        dir / "stage-sim.log");
    for (int i = 0; i < 500 && !std::filesystem::exists(dir / "stage"); ++i)
        std::this_thread::sleep_for(10ms);
    return sim;
}

std::vector<std::string> acquire_args(const std::filesystem::path& dir,
                                      const std::filesystem::path& plan, bool resume) {
    return test::acquire_cli_args(
        dir, plan, "sim://uniform?width=32&height=24&counts=1200&noise=4&fps=100&fpa_k=305",
        resume);
}

TEST(Acquire, FullRunProducesAValidCompleteSession) {
    test::TempDir tmp;
    test::write_text(tmp / "plan.yaml",
                     "frames_per_angle: 6\nsettle_s: 0.01\nmetadata: {site: test bench}\n");
    auto sim = start_stage_sim(tmp.path(), "2000");
    Child acquire(acquire_args(tmp.path(), tmp / "plan.yaml", false), tmp / "acquire.log");
    ASSERT_EQ(acquire.wait(), 0) << read_file(tmp / "acquire.log");
    const SessionManifest m = read_session(tmp / "session");
    EXPECT_TRUE(m.complete);
    ASSERT_EQ(m.records.size(), 4u);
    EXPECT_EQ(m.stage.model, "K10CR1");
    EXPECT_DOUBLE_EQ(m.stage.counts_per_degree, 409600.0 / 3.0);
    EXPECT_EQ(m.camera.width, 32);
    EXPECT_EQ(m.metadata.at("site"), "test bench");
    for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(m.records[i].angle_deg_requested, 45.0 * static_cast<double>(i));
        EXPECT_NEAR(m.records[i].angle_deg_measured, 45.0 * static_cast<double>(i), 1e-5);
        EXPECT_EQ(m.records[i].frames, 6);
        EXPECT_EQ(*m.records[i].fpa_temperature_k, 305.0);
        const Image img = read_session_frame(tmp / "session", m, m.records[i]);
        EXPECT_NEAR(channel_stats(img.channel("counts")).mean, 1200.0, 1.0);
    }
    EXPECT_THAT(read_file(tmp / "acquire.log"), ::testing::HasSubstr("session complete"));
    // A second run into the same directory without --resume is refused and changes nothing.
    Child again(acquire_args(tmp.path(), tmp / "plan.yaml", false), tmp / "again.log");
    EXPECT_EQ(again.wait(), 1);
    EXPECT_THAT(read_file(tmp / "again.log"), ::testing::HasSubstr("not empty"));
}

TEST(Acquire, KilledMidSessionAndResumedLosesAndDuplicatesNothing) {
    test::TempDir tmp;
    test::write_text(tmp / "plan.yaml", "frames_per_angle: 5\nsettle_s: 0.01\nrepeats: 3\n");
    // 90°/s: each step spends ~0.5 s moving, so the kill lands mid-session.
    auto sim = start_stage_sim(tmp.path(), "90");
    const auto manifest = tmp / "session" / "session.json";
    {
        Child acquire(acquire_args(tmp.path(), tmp / "plan.yaml", false), tmp / "first.log");
        std::size_t recorded = 0;
        for (int i = 0; i < 3000 && recorded < 3; ++i) {
            std::this_thread::sleep_for(10ms);
            try {
                recorded = nlohmann::json::parse(read_file(manifest)).at("records").size();
            } catch (const std::exception&) {
                recorded = 0;  // not created yet
            }
        }
        ASSERT_GE(recorded, 3u) << read_file(tmp / "first.log");
        acquire.signal(SIGKILL);
        EXPECT_EQ(acquire.wait(), 128 + SIGKILL);
    }
    const SessionManifest before = read_session(tmp / "session");  // consistent after kill -9
    EXPECT_FALSE(before.complete);
    ASSERT_LT(before.records.size(), 12u);
    std::map<std::string, std::string> bytes_before;
    for (const auto& r : before.records) bytes_before[r.file] = read_file(tmp / "session" / r.file);

    Child resume(acquire_args(tmp.path(), tmp / "plan.yaml", true), tmp / "resume.log");
    ASSERT_EQ(resume.wait(), 0) << read_file(tmp / "resume.log");
    const SessionManifest after = read_session(tmp / "session");
    EXPECT_TRUE(after.complete);
    const auto steps = plan_steps(CapturePlan::load(tmp / "plan.yaml"));
    ASSERT_EQ(after.records.size(), steps.size());
    std::set<std::string> files;
    for (std::size_t i = 0; i < steps.size(); ++i) {
        EXPECT_EQ(after.records[i].file, steps[i].file);
        files.insert(after.records[i].file);
    }
    EXPECT_EQ(files.size(), 12u);  // no duplicates
    for (std::size_t i = 0; i < before.records.size(); ++i)
        EXPECT_EQ(after.records[i], before.records[i]);
    for (const auto& [file, bytes] : bytes_before)
        EXPECT_EQ(read_file(tmp / "session" / file), bytes) << file;
    const auto on_disk =
        std::distance(std::filesystem::directory_iterator(tmp / "session" / "frames"), {});
    EXPECT_EQ(on_disk, 12);  // no orphans or temporaries left
}

TEST(Acquire, InterruptStopsCleanlyAndSaysHowToResume) {
    test::TempDir tmp;
    test::write_text(tmp / "plan.yaml", "frames_per_angle: 5\nsettle_s: 0.01\nrepeats: 3\n");
    auto sim = start_stage_sim(tmp.path(), "90");
    Child acquire(acquire_args(tmp.path(), tmp / "plan.yaml", false), tmp / "acquire.log");
    for (int i = 0; i < 3000 && !std::filesystem::exists(tmp / "session" / "session.json"); ++i)
        std::this_thread::sleep_for(10ms);
    std::this_thread::sleep_for(300ms);
    acquire.signal(SIGTERM);  // as Ctrl-C does with SIGINT
    EXPECT_EQ(acquire.wait(), 1);
    const std::string log = read_file(tmp / "acquire.log");
    EXPECT_THAT(log, ::testing::HasSubstr("interrupted"));
    EXPECT_THAT(log, ::testing::HasSubstr("--resume"));
    const SessionManifest m = read_session(tmp / "session");
    EXPECT_FALSE(m.complete);
    EXPECT_LT(m.records.size(), 12u);
}

}  // namespace
}  // namespace tirpol::acquisition
