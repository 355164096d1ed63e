// A capture plan run from the live view writes the same session `tirpol acquire` writes (complete,
// every step once), a stopped one keeps its steps and resumes to completion, and the polarizer
// cycle is paused meanwhile and continues after.

#include "capture_control.h"

#include <gtest/gtest.h>

#include <set>
#include <thread>

#include "sim_rig.h"
#include "test_support.h"
#include "tirpol/core/error.h"
#include "tirpol/core/session.h"

namespace tirpol::live {
namespace {

using namespace std::chrono_literals;

bool finished(const CaptureState& s) {
    return s.phase == CapturePhase::Complete || s.phase == CapturePhase::Stopped ||
           s.phase == CapturePhase::Failed;
}

/// The cycling rig plus the capture control a page drives (2 frames per angle, no settle for the
/// cycle).
struct LiveRig : test::CyclingRig {
    CaptureControl capture;
    explicit LiveRig(double deg_per_s)
        : CyclingRig(test::PolarizedSource{}, deg_per_s, 2, 0.0),
          capture(feed, *rig.stage, &cycle) {}
};

TEST(CaptureControl, WritesACompleteSessionAndTheCycleResumesAfter) {
    test::TempDir dir("tirpol-live-capture");
    test::write_text(dir / "plan.yaml", "frames_per_angle: 3\nsettle_s: 0.05\nrepeats: 2\n");
    LiveRig live(360.0);
    ASSERT_TRUE(test::wait_until([&] { return live.cycle.status().cycles >= 1; }, 60s));
    live.capture.start({dir / "plan.yaml", dir / "session", false});
    EXPECT_THROW(live.capture.start({dir / "plan.yaml", dir / "other", false}),
                 Error);  // one at a time
    ASSERT_TRUE(test::wait_until([&] { return finished(live.capture.state()); }, 120s));
    const CaptureState s = live.capture.state();
    ASSERT_EQ(s.phase, CapturePhase::Complete) << s.message;
    EXPECT_EQ(s.steps_total, 8u);
    EXPECT_EQ(s.steps_recorded, 8u);
    const SessionManifest m = read_session(dir / "session");
    EXPECT_TRUE(m.complete);
    ASSERT_EQ(m.records.size(), 8u);
    for (const auto& r : m.records) EXPECT_EQ(r.frames, 3);
    EXPECT_EQ(m.camera.width, 16);
    const auto cycles = live.cycle.status().cycles;
    EXPECT_TRUE(test::wait_until([&] { return live.cycle.status().cycles > cycles; }, 60s))
        << "the cycle did not resume";
}

TEST(CaptureControl, AStoppedCaptureKeepsItsStepsAndResumes) {
    test::TempDir dir("tirpol-live-capture");
    // Moves of 45° at 30°/s take 1.5 s: Stop lands mid-move or mid-step.
    test::write_text(dir / "plan.yaml", "frames_per_angle: 3\nsettle_s: 0.05\n");
    LiveRig live(30.0);
    live.capture.start({dir / "plan.yaml", dir / "session", false});
    ASSERT_TRUE(test::wait_until([&] { return live.capture.state().steps_recorded >= 1; }, 120s));
    live.capture.stop();
    ASSERT_TRUE(test::wait_until([&] { return finished(live.capture.state()); }, 30s));
    const CaptureState stopped = live.capture.state();
    EXPECT_EQ(stopped.phase, CapturePhase::Stopped) << stopped.message;
    EXPECT_NE(stopped.message.find("--resume"), std::string::npos) << stopped.message;
    const SessionManifest partial = read_session(dir / "session");
    EXPECT_FALSE(partial.complete);
    ASSERT_GE(partial.records.size(), 1u);
    ASSERT_LT(partial.records.size(), 4u);

    EXPECT_THROW(live.capture.start({dir / "plan.yaml", dir / "session", false}),
                 Error);  // not empty: resume it
    live.capture.start({dir / "plan.yaml", dir / "session", true});
    ASSERT_TRUE(test::wait_until([&] { return finished(live.capture.state()); }, 120s));
    ASSERT_EQ(live.capture.state().phase, CapturePhase::Complete) << live.capture.state().message;
    const SessionManifest m = read_session(dir / "session");
    EXPECT_TRUE(m.complete);
    std::set<std::string> files;
    for (const auto& r : m.records) EXPECT_TRUE(files.insert(r.file).second) << r.file << " twice";
    EXPECT_EQ(files.size(), 4u);
    for (std::size_t i = 0; i < partial.records.size(); ++i)
        EXPECT_EQ(m.records[i], partial.records[i]);
}

}  // namespace
}  // namespace tirpol::live
