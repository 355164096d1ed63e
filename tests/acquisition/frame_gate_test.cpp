// FrameGate (docs/acquisition-cameras.md, "Timing model"): a frame belongs to a step only if the
// lower bound of its exposure start, reception − 1.5 frame periods, is at or after the step's
// settle end.

#include "tirpol/acquisition/frame_gate.h"

#include <gtest/gtest.h>

namespace tirpol::acquisition {
namespace {

constexpr std::int64_t kMs = 1'000'000;

Frame received(std::uint64_t id, std::int64_t host_ns) {
    Frame f;
    f.frame_id = id;
    f.host_timestamp_ns = host_ns;
    return f;
}

TEST(FrameGate, AFrameReceivedWithinOneAndAHalfPeriodsOfTheSettleEndIsStale) {
    // 30 Hz: period 33.33 ms, window 50 ms. Reception marks the end of readout: a frame received
    // 40 ms after the settle end integrated from ≈ 7 ms before it.
    FrameGate gate(30.0);
    EXPECT_NEAR(static_cast<double>(gate.exposure_window_ns()), 50e6, 1.0);
    const std::int64_t settle_end = 1'000'000 * kMs;
    EXPECT_FALSE(gate.exposed_after(received(1, settle_end - 500 * kMs),
                                    settle_end));  // queued during the move
    EXPECT_FALSE(gate.exposed_after(received(2, settle_end + 40 * kMs), settle_end));
    EXPECT_TRUE(gate.exposed_after(received(3, settle_end + 51 * kMs), settle_end));
    EXPECT_TRUE(gate.exposed_after(received(4, settle_end + 84 * kMs), settle_end));
}

TEST(FrameGate, WithoutANominalRateTheShortestIntervalPerFrameIdIsThePeriod) {
    FrameGate gate(std::nullopt);
    EXPECT_EQ(gate.exposure_window_ns(), 300 * kMs);  // 1.5 × the 0.2 s assumed before any interval
    const std::int64_t t0 = 5'000 * kMs;
    gate.exposed_after(received(10, t0), 0);
    gate.exposed_after(received(12, t0 + 20 * kMs), 0);  // a drop: two ids in 20 ms → 10 ms per id
    gate.exposed_after(received(13, t0 + 35 * kMs), 0);  // a late reception does not lengthen it
    EXPECT_EQ(gate.exposure_window_ns(), 15 * kMs);
}

TEST(FrameGate, ACameraSlowerThanItsNominalRateIsGatedOnItsTruePeriod) {
    // It reports 1000 Hz (window 1.5 ms) but frames arrive every 16 ms: integration spans ~16 ms.
    FrameGate gate(1000.0);
    EXPECT_EQ(gate.exposure_window_ns(), 1'500'000);
    const std::int64_t t0 = 7'000 * kMs;
    gate.exposed_after(received(1, t0), 0);
    gate.exposed_after(received(2, t0 + 16 * kMs), 0);
    EXPECT_EQ(gate.exposure_window_ns(), 24 * kMs);
    EXPECT_FALSE(gate.exposed_after(received(3, t0 + 32 * kMs), t0 + 10 * kMs));
}

TEST(FrameGate, AHostStampDelayedByAStarvedThreadIsCorrectedFromTheDeviceClock) {
    // Device clock = host − 5 s (an arbitrary offset) + 2 ms of transfer latency for frames 1
    // and 2. Frame 3 was exposed at the same cadence but its host stamp is 40 ms late (the
    // receiving thread waited for the CPU): from the device clock it arrived at t0 + 66 ms, before
    // the settle end.
    FrameGate gate(30.0);
    const std::int64_t t0 = 9'000 * kMs, offset = 5'000 * kMs;
    auto frame = [&](std::uint64_t id, std::int64_t exposed_end, std::int64_t latency) {
        Frame f = received(id, exposed_end + latency);
        f.device_timestamp_ns = exposed_end - offset;
        return f;
    };
    EXPECT_FALSE(gate.exposed_after(frame(1, t0, 2 * kMs), t0));
    EXPECT_FALSE(gate.exposed_after(frame(2, t0 + 33 * kMs, 2 * kMs), t0));
    const std::int64_t settle_end = t0 + 30 * kMs;
    EXPECT_FALSE(gate.exposed_after(frame(3, t0 + 66 * kMs, 42 * kMs),
                                    settle_end));  // host alone would pass: 108 − 50 ≥ 30
    EXPECT_TRUE(gate.exposed_after(frame(4, t0 + 99 * kMs, 2 * kMs), settle_end));
}

TEST(FrameGate, DeliveredRateCountsReceivedFramesAndSkipsPauses) {
    FrameGate gate(100.0);
    EXPECT_FALSE(gate.delivered_rate_hz());
    std::int64_t t = 1'000 * kMs;
    std::uint64_t id = 1;
    for (int i = 0; i < 11; ++i)
        gate.exposed_after(received(id++, t += 20 * kMs), 0);  // 50 Hz delivered
    id += 1;                                                   // one dropped
    gate.exposed_after(received(id++, t += 40 * kMs), 0);
    gate.exposed_after(received(id++, t += 5'000 * kMs),
                       0);  // a 5 s pause (e.g. a software trigger waiting)
    // 11 intervals in 240 ms: 45.8 Hz, what reached the host (not the 100 Hz asked for).
    ASSERT_TRUE(gate.delivered_rate_hz());
    EXPECT_NEAR(*gate.delivered_rate_hz(), 11.0 / 0.240, 1e-9);
}

}  // namespace
}  // namespace tirpol::acquisition
