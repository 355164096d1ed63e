// The live Stokes image of a known polarized source, through a stage that takes time to turn and a
// free-running camera: DoLP and AoP come out as the source's (the cycle's frame gating keeps the
// frames exposed during moves out; they would bias both), and pausing hands the stage over.

#include "polarizer_cycle.h"

#include <gtest/gtest.h>

#include <thread>

#include "sim_rig.h"
#include "tirpol/core/error.h"
#include "tirpol/core/image.h"

namespace tirpol::live {
namespace {

using namespace std::chrono_literals;

TEST(PolarizerCycle, StokesOfAKnownSourceThroughATurningStage) {
    const test::PolarizedSource source;  // S0 4000 counts, DoLP 0.3, AoP 30°
    // 45° moves at 180°/s take 0.25 s: ~25 frames exposed mid-move each; 8 frames kept per angle.
    test::CyclingRig live(source, 180.0, 8, 0.05);
    const PolarizerCycle& cycle = live.cycle;
    ASSERT_TRUE(test::wait_until([&] { return cycle.status().cycles >= 2; }, 60s))
        << cycle.status().state << " " << cycle.status().error;
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
}

TEST(PolarizerCycle, PauseStopsCommandingTheStageUntilResumed) {
    test::CyclingRig live(test::PolarizedSource{}, 720.0, 2, 0.0);
    PolarizerCycle& cycle = live.cycle;
    acquisition::Stage& stage = *live.rig.stage;
    ASSERT_TRUE(test::wait_until([&] { return cycle.status().cycles >= 1; }, 60s));
    cycle.pause();
    EXPECT_EQ(cycle.status().state, "paused");
    const auto cycles = cycle.status().cycles;
    const double angle = stage.position_deg().value();
    std::this_thread::sleep_for(500ms);
    EXPECT_EQ(cycle.status().cycles, cycles);
    EXPECT_DOUBLE_EQ(stage.position_deg().value(), angle) << "the stage moved while paused";
    cycle.resume();
    EXPECT_TRUE(test::wait_until([&] { return cycle.status().cycles > cycles; }, 60s));
}

TEST(PolarizerCycle, FewerThanThreeAnglesIsAnError) {
    test::SimRig rig(test::PolarizedSource{}, 0.0);
    live::FrameFeed feed(*rig.camera);
    const DisplayConverter converter(rig.camera->info(), nullptr, DisplayUnit::Counts);
    CycleOptions options;
    options.angles_deg = {0.0, 90.0};
    EXPECT_THROW(PolarizerCycle(feed, *rig.stage, converter, options), Error);
}

}  // namespace
}  // namespace tirpol::live
