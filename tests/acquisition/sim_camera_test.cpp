// sim:// cameras: the generator sees the current polarizer angle, temporal noise has the configured
// statistics, counts are quantised and clipped like an ADC, injected drops show up as id gaps.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <numbers>
#include <thread>

#include "tirpol/acquisition/frame_gate.h"
#include "tirpol/acquisition/sim/simulated_camera.h"
#include "tirpol/core/error.h"

namespace tirpol::acquisition {
namespace {

using namespace std::chrono_literals;

double mean_of(const std::vector<float>& v) {
    double s = 0.0;
    for (float x : v) s += x;
    return s / static_cast<double>(v.size());
}

TEST(SimulatedCamera, GeneratorFollowsThePolarizerAngleMalusLaw) {
    // An ideal linear polarizer in front of partially polarized light: I(θ) = (S0 + S1 cos 2θ + S2
    // sin 2θ) / 2 (Malus's law in Stokes form, the paper's eqs 14–16 invert it). Recover S0, S1, S2
    // from 0/45/90/135°.
    const double s0 = 10000.0, s1 = -600.0, s2 = 250.0;
    std::atomic<double> angle{0.0};
    SimulatedCameraConfig config;
    config.width = 8;
    config.height = 4;
    config.frame_rate_hz = 200.0;
    SimulatedCamera camera(
        config,
        [&](double angle_deg, std::vector<float>& out) {
            const double t = 2.0 * angle_deg * std::numbers::pi / 180.0;
            std::fill(out.begin(), out.end(),
                      static_cast<float>(0.5 * (s0 + s1 * std::cos(t) + s2 * std::sin(t))));
        },
        [&] { return angle.load(); });
    ASSERT_TRUE(camera.start().ok());
    std::map<int, double> intensity;
    for (int a : {0, 45, 90, 135}) {
        angle = a;
        // The camera free-runs: frames queued before the turn still show the old angle.
        const std::int64_t turned_ns = host_realtime_ns();
        Frame frame = camera.grab(1s).value();
        while (frame.host_timestamp_ns <= turned_ns) frame = camera.grab(1s).value();
        intensity[a] = mean_of(frame.counts);
    }
    // Counts are rounded to integers: each I is within 0.5 of the exact value.
    EXPECT_NEAR(intensity[0] + intensity[90], s0, 1.0);
    EXPECT_NEAR(intensity[0] - intensity[90], s1, 1.0);
    EXPECT_NEAR(intensity[45] - intensity[135], s2, 1.0);
}

TEST(SimulatedCamera, TemporalNoiseHasTheConfiguredStandardDeviation) {
    auto camera = open_simulated_camera(
        "sim://uniform?width=64&height=64&counts=5000&noise=20&seed=7&fps=500&buffers=64");
    ASSERT_TRUE(camera->start().ok());
    FrameAverager averager;
    for (int i = 0; i < 50; ++i) averager.add(camera->grab(1s).value());
    // Per-pixel std over 50 frames, averaged over 4096 pixels: σ² = 20² + 1/12 (rounding) → 20.002;
    // the spread of the estimate is ≈ σ / sqrt(2 · 49 · 4096) ≈ 0.03 (plus the small-sample bias of
    // s, ≈ 0.5 %).
    EXPECT_NEAR(mean_of(averager.stddev()), 20.0, 0.3);
    // Mean of 50 × 4096 samples: within 5 standard errors of 5000.
    EXPECT_NEAR(mean_of(averager.mean()), 5000.0, 5.0 * 20.0 / std::sqrt(50.0 * 4096.0));
}

TEST(SimulatedCamera, CountsAreIntegersClippedToTheAdcRange) {
    auto high = open_simulated_camera("sim://uniform?width=16&height=16&counts=70000&noise=5");
    ASSERT_TRUE(high->start().ok());
    const Frame saturated = high->grab(1s).value();
    for (float v : saturated.counts) EXPECT_EQ(v, 65535.0f);
    auto low = open_simulated_camera("sim://uniform?width=16&height=16&counts=3&noise=50&bits=14");
    ASSERT_TRUE(low->start().ok());
    EXPECT_EQ(low->info().pixel_format, "Mono14");
    const Frame dark = low->grab(1s).value();
    for (float v : dark.counts) {
        EXPECT_GE(v, 0.0f);
        EXPECT_LE(v, 16383.0f);
        EXPECT_EQ(v, std::round(v));
    }
}

TEST(SimulatedCamera, InjectedDropsAreIdGapsAndTimestampsFollowTheFrameRate) {
    // A queue of 4000 buffers: no frame is lost for want of a buffer, only the injected drops.
    auto camera = open_simulated_camera(
        "sim://uniform?width=4&height=4&fps=2000&drop=0.2&seed=3&buffers=4000");
    ASSERT_TRUE(camera->start().ok());
    std::vector<Frame> frames;
    for (int i = 0; i < 2000; ++i) frames.push_back(camera->grab(1s).value());
    const auto last_grab = std::chrono::steady_clock::now();
    std::uint64_t gaps = 0;
    for (std::size_t i = 1; i < frames.size(); ++i) {
        ASSERT_GT(frames[i].frame_id, frames[i - 1].frame_id);
        gaps += frames[i].frame_id - frames[i - 1].frame_id - 1;
        EXPECT_GT(frames[i].device_timestamp_ns, frames[i - 1].device_timestamp_ns);
    }
    // 2000 Hz on the device's own clock: never faster than 0.5 ms per id on average (slower when
    // the loaded machine delays the camera's thread).
    EXPECT_GE(frames.back().device_timestamp_ns - frames.front().device_timestamp_ns,
              static_cast<std::int64_t>(frames.back().frame_id - frames.front().frame_id) *
                  500'000 * 95 / 100);
    const StreamStatistics stats = camera->statistics();
    const double after_last_grab_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - last_grab).count();
    EXPECT_EQ(stats.delivered, 2000u);
    // Every drop before the last frame grabbed is a gap in the ids. The camera keeps streaming
    // until statistics() is read, so drops of later ids may be counted too: at most the frames its
    // 2000 Hz clock exposes in that interval (+2 for the ones in flight).
    const std::uint64_t seen_as_gaps = gaps + (frames.front().frame_id - 1);
    EXPECT_GE(stats.dropped, seen_as_gaps);
    EXPECT_LE(stats.dropped,
              seen_as_gaps + static_cast<std::uint64_t>(std::ceil(after_last_grab_s * 2000.0)) + 2);
    // Lost fraction p = 0.2: dropped / (dropped + delivered) has standard error ≈ 0.008 over ~2500
    // ids.
    const double fraction =
        static_cast<double>(stats.dropped) / static_cast<double>(stats.dropped + stats.delivered);
    EXPECT_NEAR(fraction, 0.2, 0.04);
}

TEST(SimulatedCamera, FreeRunsOnItsOwnClockAndLosesFramesWhenItsQueueIsFull) {
    // Nobody grabs for 0.3 s at 100 Hz: about 30 frames are exposed, the 4-buffer queue keeps the
    // first 4 (the oldest, as an Aravis stream does) and the rest are lost.
    auto camera = open_simulated_camera("sim://uniform?width=4&height=4&fps=100&buffers=4");
    const std::int64_t started_ns = host_realtime_ns();
    ASSERT_TRUE(camera->start().ok());
    std::this_thread::sleep_for(300ms);
    std::vector<Frame> frames;
    for (int i = 0; i < 6; ++i) frames.push_back(camera->grab(1s).value());
    const std::int64_t grabbed_ns = host_realtime_ns();
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(frames[i].frame_id, static_cast<std::uint64_t>(i + 1));
        EXPECT_LT(frames[i].host_timestamp_ns,
                  started_ns + 150'000'000);  // exposed long before the grab
    }
    EXPECT_GT(frames[4].frame_id, 20u);  // the next one after the gap is a fresh frame
    EXPECT_GT(frames[4].host_timestamp_ns, grabbed_ns - 100'000'000);
    EXPECT_GE(camera->statistics().dropped, 15u);
}

TEST(SimulatedCamera, SameSeedGivesTheSameFrames) {
    auto a = open_simulated_camera("sim://uniform?width=8&height=8&noise=10&seed=11");
    auto b = open_simulated_camera("sim://uniform?width=8&height=8&noise=10&seed=11");
    ASSERT_TRUE(a->start().ok());
    ASSERT_TRUE(b->start().ok());
    EXPECT_EQ(a->grab(1s).value().counts, b->grab(1s).value().counts);
}

TEST(SimulatedCamera, GrabBeforeStartIsAnError) {
    auto camera = open_simulated_camera("sim://uniform");
    const auto frame = camera->grab(1s);
    ASSERT_FALSE(frame.ok());
    EXPECT_EQ(frame.error().code, DeviceErrorCode::InvalidArgument);
    EXPECT_EQ(camera->info().width, 640);
    EXPECT_EQ(camera->info().height, 512);
}

TEST(SimulatedCamera, MicrogridCameraReportsItsPatternAndStreamsPolarizedFormats) {
    // A microgrid camera (sim://…&microgrid=) says so in CameraInfo, as an Aravis polarization
    // camera does, and takes the polarized pixel formats; its ADC depth follows the format.
    auto camera =
        open_simulated_camera("sim://uniform?width=8&height=4&counts=8000&fps=200&microgrid=sony");
    CameraInfo info = camera->info();
    ASSERT_TRUE(info.microgrid_pattern_deg);
    EXPECT_EQ(*info.microgrid_pattern_deg, (std::array<double, 4>{90.0, 45.0, 135.0, 0.0}));
    EXPECT_EQ(info.pixel_format, "PolarizeMono16");
    ASSERT_TRUE(camera->set_pixel_format("PolarizeMono12p").ok());
    info = camera->info();
    EXPECT_EQ(info.pixel_format, "PolarizeMono12p");
    EXPECT_EQ(info.bits_per_pixel, 12);
    ASSERT_TRUE(camera->start().ok());
    const Frame frame = camera->grab(1s).value();
    for (float c : frame.counts) EXPECT_EQ(c, 4095.0f) << "8000 counts clip at 12 bits";

    auto plain = open_simulated_camera("sim://uniform?width=8&height=4");
    EXPECT_FALSE(plain->info().microgrid_pattern_deg);
    EXPECT_FALSE(plain->set_pixel_format("PolarizeMono12p").ok())
        << "a camera without a microgrid has no polarized format";
    EXPECT_THROW(open_simulated_camera("sim://uniform?microgrid=0,1,2"), Error);
}

TEST(SimulatedCamera, BadUrisNameTheOffendingPart) {
    try {
        open_simulated_camera("sim://uniform?widht=10");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("widht"), std::string::npos) << e.what();
    }
    try {
        open_simulated_camera("sim://uniform?noise=lots");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("noise=lots"), std::string::npos) << e.what();
    }
    EXPECT_THROW(open_simulated_camera("sim://uniform?drop=1.5"), Error);
    EXPECT_THROW(open_simulated_camera("sim://scene.yaml"), Error);
}

}  // namespace
}  // namespace tirpol::acquisition
