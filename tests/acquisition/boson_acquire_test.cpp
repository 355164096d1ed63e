// `tirpol acquire --camera-control boson://PTY` end to end: the CLI and tirpol-boson-sim as
// separate processes, the control link through the real serial code. The sim:// camera's video does
// not come from this core (a separate process), so this checks the schedule and the record, not the
// frames (capture_ffc_test.cpp checks those on one in-process core).

#include <gtest/gtest.h>

#include <csignal>
#include <thread>

#include "child_process.h"
#include "test_support.h"
#include "tirpol/acquisition/capture.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/session.h"

namespace tirpol::acquisition {
namespace {

using namespace std::chrono_literals;

std::unique_ptr<test::ChildProcess> start_boson_sim(const std::filesystem::path& dir) {
    auto sim = std::make_unique<test::ChildProcess>(
        std::vector<std::string>{TIRPOL_BOSON_SIM_PATH, "--link", (dir / "boson").string(),
                                 "--ffc-s", "0.2"},
        dir / "boson-sim.log");
    for (int i = 0; i < 500 && !std::filesystem::exists(dir / "boson"); ++i)
        std::this_thread::sleep_for(10ms);
    return sim;
}

int run_acquire(const std::filesystem::path& dir, const std::string& ffc, const char* log) {
    test::ChildProcess acquire(
        {TIRPOL_CLI_PATH, "acquire", (dir / "plan.yaml").string(), "--camera",
         "sim://uniform?width=16&height=12&counts=1200&noise=2&fps=100", "--stage", "sim://",
         "--camera-control", "boson://" + (dir / "boson").string(), "--ffc", ffc, "-o",
         (dir / "session").string(), "--non-interactive"},
        dir / log);
    return acquire.wait_for(120s).value_or(-1);
}

TEST(BosonAcquire, TheCliRunsAnFfcBeforeEachCycleAndRecordsIt) {
    test::TempDir tmp;
    write_file_atomic(tmp / "plan.yaml", "frames_per_angle: 3\nsettle_s: 0\nrepeats: 2\n");
    auto sim = start_boson_sim(tmp.path());
    ASSERT_TRUE(std::filesystem::exists(tmp / "boson"))
        << "tirpol-boson-sim did not create its link";
    ASSERT_EQ(run_acquire(tmp.path(), "every-cycle", "acquire.log"), 0)
        << read_file(tmp / "acquire.log");
    const SessionManifest m = read_session(tmp / "session");
    EXPECT_TRUE(m.complete);
    EXPECT_EQ(m.records.size(), 8u);
    ASSERT_EQ(m.ffc_events.size(), 2u);
    for (int i = 0; i < 2; ++i) {
        const FfcEvent& e = m.ffc_events[static_cast<std::size_t>(i)];
        EXPECT_EQ(e.kind, FfcEvent::Kind::Scheduled);
        EXPECT_EQ(e.repeat, i);
        EXPECT_NEAR(e.fpa_temperature_k.value_or(0.0), 308.15,
                    0.051);  // the simulator's default FPA, 0.1 °C steps
        EXPECT_GT(e.device_frame_count.value_or(0), 0);
    }
    EXPECT_NE(read_file(tmp / "acquire.log").find("2 scheduled between cycles, 0 detected"),
              std::string::npos)
        << read_file(tmp / "acquire.log");
    sim->signal(SIGTERM);
    EXPECT_EQ(sim->wait_for(5s), 0);
    // `tirpol info SESSION` summarises what a reviewer audits.
    test::ChildProcess info({TIRPOL_CLI_PATH, "info", (tmp / "session").string()},
                            tmp / "info.log");
    ASSERT_EQ(info.wait_for(60s).value_or(-1), 0) << read_file(tmp / "info.log");
    const std::string out = read_file(tmp / "info.log");
    EXPECT_NE(out.find("records: 8 (8 polarizer, 0 reference), 24 frames averaged"),
              std::string::npos)
        << out;
    EXPECT_NE(out.find("audit: 8 of 8 records per frame; 24 frames with a device clock"),
              std::string::npos)
        << out;
    EXPECT_NE(out.find("flat-field corrections: 2 scheduled between cycles, 0 detected"),
              std::string::npos)
        << out;
}

TEST(BosonAcquire, ABadScheduleIsRefusedByName) {
    EXPECT_THROW(
        {
            try {
                parse_ffc_schedule("every:0");
            } catch (const Error& e) {
                EXPECT_NE(std::string(e.what()).find("--ffc 'every:0'"), std::string::npos)
                    << e.what();
                throw;
            }
        },
        Error);
    EXPECT_THROW(parse_ffc_schedule("fpa:-1"), Error);
    EXPECT_THROW(parse_ffc_schedule("sometimes"), Error);
    EXPECT_EQ(parse_ffc_schedule("every:3").every_n_cycles, 3);
    EXPECT_EQ(parse_ffc_schedule("fpa:0.25").fpa_delta_k, 0.25);
    EXPECT_EQ(parse_ffc_schedule("fpa:0.25").schedule, FfcOptions::Schedule::FpaDelta);
    EXPECT_THROW((void)open_ffc_control("flir:///dev/video0"), Error);
    auto absent = open_ffc_control("boson:///dev/nonexistent-boson");
    ASSERT_FALSE(absent);
    EXPECT_NE(absent.error().message.find("/dev/nonexistent-boson"), std::string::npos)
        << absent.error().message;
}

}  // namespace
}  // namespace tirpol::acquisition
