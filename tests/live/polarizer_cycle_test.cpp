// The live Stokes image of a known polarized source, through a stage that takes time to turn and a
// free-running camera: DoLP and AoP come out as the source's (the cycle's frame gating keeps the
// frames exposed during moves out; they would bias both), and pausing hands the stage over.

#include <gtest/gtest.h>

#include <thread>

#include "sim_rig.h"
#include "tirpol/core/error.h"
#include "tirpol/core/image.h"
#include "tirpol/live/polarizer_cycle.h"

namespace tirpol::live {
namespace {

using namespace std::chrono_literals;

bool wait_for(const std::function<bool()>& condition, std::chrono::seconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (!condition()) {
        if (std::chrono::steady_clock::now() > deadline) return false;
        std::this_thread::sleep_for(20ms);
    }
    return true;
}

TEST(PolarizerCycle, StokesOfAKnownSourceThroughATurningStage) {
    const test::PolarizedSource source;  // S0 4000 counts, DoLP 0.3, AoP 30°
    test::SimRig rig(source, 180.0);     // 45° moves take 0.25 s: ~25 frames exposed mid-move each
    FrameFeed feed(*rig.camera);
    const DisplayConverter converter(rig.camera->info(), nullptr, DisplayUnit::Counts);
    CycleOptions options;
    options.frames_per_angle = 8;
    options.settle_s = 0.05;
    PolarizerCycle cycle(feed, *rig.stage, converter, options);
    ASSERT_TRUE(feed.start().ok());
    cycle.start();
    ASSERT_TRUE(wait_for([&] { return cycle.status().cycles >= 2; }, 60s)) << cycle.status().state << " " << cycle.status().error;
    const auto stokes = cycle.stokes().latest().value;
    ASSERT_TRUE(stokes);
    const auto s0 = channel_stats(stokes->channel("S0"));
    const auto s1 = channel_stats(stokes->channel("S1"));
    const auto s2 = channel_stats(stokes->channel("S2"));
    const auto dolp = channel_stats(stokes->channel("DoLP"));
    const auto aop = channel_stats(stokes->channel("AoP"));
    // Noise: σ = 2 counts per frame, 8 frames → σ(S0) ≈ 1 count; bounds at several σ.
    EXPECT_NEAR(s0.mean, source.s0, 5.0);
    EXPECT_NEAR(s1.mean, source.s1(), 5.0);
    EXPECT_NEAR(s2.mean, source.s2(), 5.0);
    EXPECT_NEAR(dolp.mean, source.dolp, 0.005);
    EXPECT_NEAR(aop.mean, source.aop_deg, 0.5);
    EXPECT_EQ(stokes->channel_names().size() >= 5, true);
    cycle.stop();
    feed.stop();
}

TEST(PolarizerCycle, PauseStopsCommandingTheStageUntilResumed) {
    test::SimRig rig(test::PolarizedSource{}, 720.0);
    FrameFeed feed(*rig.camera);
    const DisplayConverter converter(rig.camera->info(), nullptr, DisplayUnit::Counts);
    CycleOptions options;
    options.frames_per_angle = 2;
    options.settle_s = 0.0;
    PolarizerCycle cycle(feed, *rig.stage, converter, options);
    ASSERT_TRUE(feed.start().ok());
    cycle.start();
    ASSERT_TRUE(wait_for([&] { return cycle.status().cycles >= 1; }, 60s));
    cycle.pause();
    EXPECT_EQ(cycle.status().state, "paused");
    const auto cycles = cycle.status().cycles;
    const double angle = rig.stage->position_deg().value();
    std::this_thread::sleep_for(500ms);
    EXPECT_EQ(cycle.status().cycles, cycles);
    EXPECT_DOUBLE_EQ(rig.stage->position_deg().value(), angle) << "the stage moved while paused";
    cycle.resume();
    EXPECT_TRUE(wait_for([&] { return cycle.status().cycles > cycles; }, 60s));
    cycle.stop();
    feed.stop();
}

TEST(PolarizerCycle, FewerThanThreeAnglesIsAnError) {
    test::SimRig rig(test::PolarizedSource{}, 0.0);
    FrameFeed feed(*rig.camera);
    const DisplayConverter converter(rig.camera->info(), nullptr, DisplayUnit::Counts);
    CycleOptions options;
    options.angles_deg = {0.0, 90.0};
    EXPECT_THROW(PolarizerCycle(feed, *rig.stage, converter, options), Error);
}

}  // namespace
}  // namespace tirpol::live
