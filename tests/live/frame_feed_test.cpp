// The grab thread drops display frames, never camera frames: a display that samples the latest
// frame slowly sees few of them, while every tap (the polarizer cycle, a capture) receives each
// frame the camera delivered, in order, and the camera itself drops none.

#include "frame_feed.h"

#include <gtest/gtest.h>

#include <thread>

#include "latest_slot.h"
#include "tapped_camera.h"
#include "tirpol/acquisition/sim/simulated_camera.h"

namespace tirpol::live {
namespace {

using namespace std::chrono_literals;

TEST(LatestSlot, ASlowReaderSeesIncreasingSequencesAndTheLastValue) {
    LatestSlot<int> slot;
    EXPECT_EQ(slot.latest().sequence, 0u);
    std::thread producer([&] {
        for (int i = 1; i <= 2000; ++i) slot.publish(std::make_shared<const int>(i));
    });
    std::uint64_t seen = 0;
    int reads = 0;
    while (seen < 2000) {
        const auto s = slot.wait_newer(seen, 2s);
        ASSERT_GT(s.sequence, seen) << "no new value within 2 s";
        EXPECT_EQ(*s.value,
                  static_cast<int>(s.sequence));  // the value published with that sequence
        seen = s.sequence;
        ++reads;
    }
    producer.join();
    EXPECT_EQ(*slot.latest().value, 2000);
    EXPECT_LE(reads, 2000);
    // Nothing newer: the wait ends at its timeout with the same snapshot.
    EXPECT_EQ(slot.wait_newer(2000, 10ms).sequence, 2000u);
}

TEST(FrameFeed, TapsGetEveryFrameInOrderWhileASlowDisplayDropsDisplayFramesOnly) {
    auto camera = acquisition::open_simulated_camera(
        "sim://uniform?width=64&height=48&counts=900&noise=3&fps=100&buffers=64");
    FrameFeed feed(*camera);
    const auto tap = feed.open_tap();
    ASSERT_TRUE(feed.start().ok());

    // A display that takes 100 ms per frame (a slow browser) for about 1.5 s.
    int displayed = 0;
    std::uint64_t after = 0;
    for (int i = 0; i < 15; ++i) {
        const auto s = feed.latest().wait_newer(after, 2s);
        ASSERT_GT(s.sequence, after);
        after = s.sequence;
        ++displayed;
        std::this_thread::sleep_for(100ms);
    }
    // The tap was not read meanwhile; it still holds every frame, consecutive ids.
    const std::size_t pending = tap->pending();
    EXPECT_GE(pending, 100u);  // ≈ 150 at 100 fps; the bound leaves room for a loaded machine
    std::uint64_t previous = 0;
    for (std::size_t i = 0; i < pending; ++i) {
        auto f = tap->next(1s);
        ASSERT_TRUE(f.ok());
        if (previous != 0)
            EXPECT_EQ(f.value().frame_id, previous + 1) << "a frame went missing from the tap";
        previous = f.value().frame_id;
    }
    feed.stop();
    const auto s = feed.statistics();
    EXPECT_EQ(s.dropped, 0u) << "the camera lost frames: the grab thread waited on the display";
    EXPECT_EQ(s.grabbed, s.delivered);
    EXPECT_LT(displayed * 3, static_cast<int>(s.grabbed)) << "the display did not skip frames";
    ASSERT_TRUE(s.frame_rate_hz.has_value());
    EXPECT_GT(*s.frame_rate_hz, 30.0);  // 100 fps nominal; generous for a loaded machine
}

TEST(FrameFeed, RecordsTheCamerasFpaTemperature) {
    auto camera =
        acquisition::open_simulated_camera("sim://uniform?width=8&height=8&fps=50&fpa_k=305.5");
    FrameFeed feed(*camera);
    ASSERT_TRUE(feed.start().ok());
    for (int i = 0; i < 100 && feed.fpa_history().empty(); ++i) std::this_thread::sleep_for(20ms);
    feed.stop();
    const auto history = feed.fpa_history();
    ASSERT_FALSE(history.empty());
    EXPECT_DOUBLE_EQ(history.front().temperature_k, 305.5);
}

TEST(TappedCamera, GrabsTheFeedsFramesFromStartAndRefusesAnotherFormat) {
    auto camera =
        acquisition::open_simulated_camera("sim://uniform?width=8&height=8&fps=100&bits=14");
    FrameFeed feed(*camera);
    ASSERT_TRUE(feed.start().ok());
    TappedCamera tapped(feed);
    EXPECT_FALSE(tapped.grab(10ms).ok());  // before start()
    ASSERT_TRUE(tapped.start().ok());
    auto a = tapped.grab(2s), b = tapped.grab(2s);
    ASSERT_TRUE(a.ok() && b.ok());
    EXPECT_EQ(b.value().frame_id, a.value().frame_id + 1);
    EXPECT_EQ(tapped.info().width, 8);
    EXPECT_TRUE(tapped.set_pixel_format(tapped.info().pixel_format).ok());
    EXPECT_FALSE(tapped.set_pixel_format("Mono8").ok());
    feed.stop();
}

}  // namespace
}  // namespace tirpol::live
