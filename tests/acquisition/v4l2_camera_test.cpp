// Requires TIRPOL_WITH_V4L2 (built only with that back end: cmake/TirpolBackends.cmake).
// The v4l2:// backend against FakeV4l2Device (tests/acquisition/fake_v4l2_device.h), a state
// machine that follows the kernel's V4L2 API documentation for memory-mapped streaming: formats,
// REQBUFS/ QUERYBUF/mmap/QBUF/STREAMON/DQBUF rules, sequence numbers, EAGAIN and poll timeouts,
// ENODEV.

#include "tirpol/acquisition/internal/v4l2_camera.h"

#include <gtest/gtest.h>

#include <thread>

#include "fake_v4l2_device.h"
#include "open_camera_error.h"
#include "test_support.h"
#include "tirpol/acquisition/camera.h"
#include "tirpol/acquisition/capture.h"
#include "tirpol/core/error.h"

namespace tirpol::acquisition {
namespace {

using namespace std::chrono_literals;
using test::FakeV4l2Device;

std::unique_ptr<Camera> open_fake(const std::shared_ptr<FakeV4l2Device>& device,
                                  V4l2CameraOptions options = {}) {
    auto camera = open_v4l2_camera("/dev/video0", options, device);
    EXPECT_TRUE(camera.ok()) << (camera.ok() ? "" : camera.error().message);
    return camera.ok() ? std::move(camera.value()) : nullptr;
}

bool matches_pattern(const Frame& frame, std::uint32_t fourcc, std::uint32_t sequence) {
    for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width; ++x)
            if (frame.counts[static_cast<std::size_t>(y * frame.width + x)] !=
                static_cast<float>(FakeV4l2Device::pattern(fourcc, static_cast<std::uint32_t>(x),
                                                           static_cast<std::uint32_t>(y),
                                                           sequence)))
                return false;
    return true;
}

TEST(V4l2Camera, StreamsY16FramesWithSequenceIdsAndTimestamps) {
    auto device = std::make_shared<FakeV4l2Device>();
    V4l2CameraOptions options;
    options.pixel_format = "Y16";
    options.frame_rate_hz = 30.0;
    auto camera = open_fake(device, options);
    ASSERT_TRUE(camera);
    EXPECT_TRUE(device->opened_nonblocking());
    const CameraInfo info = camera->info();
    EXPECT_EQ(info.uri, "v4l2:///dev/video0");
    EXPECT_EQ(info.vendor, "uvcvideo");
    EXPECT_EQ(info.model, "Boson: FLIR Video");
    EXPECT_EQ(info.pixel_format, "Y16");
    EXPECT_EQ(info.bits_per_pixel, 16);
    EXPECT_EQ(info.width, 160);
    EXPECT_EQ(info.height, 120);
    EXPECT_EQ(info.frame_rate_hz, 30.0);

    ASSERT_TRUE(camera->start().ok());
    EXPECT_TRUE(device->streaming());
    EXPECT_EQ(device->mapped_count(), 4u);
    for (std::uint32_t seq = 0; seq < 6; ++seq) {
        auto frame = camera->grab(1s);
        ASSERT_TRUE(frame.ok()) << frame.error().message;
        EXPECT_EQ(frame.value().frame_id, seq);
        EXPECT_TRUE(matches_pattern(frame.value(), V4L2_PIX_FMT_Y16, seq));
        EXPECT_EQ(frame.value().device_timestamp_ns, static_cast<std::int64_t>(seq) * 33333 * 1000);
        // Every buffer goes back to the driver after its frame is copied out.
        EXPECT_EQ(device->queued_count(), 4u);
    }
    EXPECT_EQ(camera->statistics().delivered, 6u);
    EXPECT_EQ(camera->statistics().dropped, 0u);
}

TEST(V4l2Camera, GreyFramesAreEightBit) {
    auto device = std::make_shared<FakeV4l2Device>();
    V4l2CameraOptions options;
    options.pixel_format = "GREY";
    auto camera = open_fake(device, options);
    ASSERT_TRUE(camera);
    EXPECT_EQ(camera->info().bits_per_pixel, 8);
    ASSERT_TRUE(camera->start().ok());
    auto frame = camera->grab(1s);
    ASSERT_TRUE(frame.ok());
    EXPECT_TRUE(matches_pattern(frame.value(), V4L2_PIX_FMT_GREY, 0));
}

TEST(V4l2Camera, StopUnmapsAndFreesBuffersSoStreamingCanRestart) {
    auto device = std::make_shared<FakeV4l2Device>();
    auto camera = open_fake(device);
    ASSERT_TRUE(camera);
    for (int round = 0; round < 2; ++round) {
        ASSERT_TRUE(camera->start().ok());
        ASSERT_TRUE(camera->grab(1s).ok());
        ASSERT_TRUE(camera->stop().ok());
        EXPECT_FALSE(device->streaming());
        EXPECT_EQ(device->mapped_count(), 0u);
        EXPECT_EQ(device->allocated_count(),
                  0u);  // REQBUFS(0) after munmap, else the driver says EBUSY
    }
    camera.reset();
    EXPECT_FALSE(device->is_open());
}

TEST(V4l2Camera, DriverMayGrantFewerBuffersButNotFewerThanTwo) {
    auto device = std::make_shared<FakeV4l2Device>();
    device->max_buffers = 3;
    auto camera = open_fake(device);
    ASSERT_TRUE(camera);
    ASSERT_TRUE(camera->start().ok());
    EXPECT_EQ(device->mapped_count(), 3u);
    ASSERT_TRUE(camera->grab(1s).ok());
    ASSERT_TRUE(camera->stop().ok());

    device->max_buffers = 1;
    const Status refused = camera->start();
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.error().code, DeviceErrorCode::DeviceFault);
    EXPECT_EQ(device->allocated_count(), 0u);
}

TEST(V4l2Camera, SequenceGapsAreCountedAsDroppedFrames) {
    auto device = std::make_shared<FakeV4l2Device>();
    auto camera = open_fake(device);
    ASSERT_TRUE(camera);
    ASSERT_TRUE(camera->start().ok());
    ASSERT_EQ(camera->grab(1s).value().frame_id, 0u);
    device->skip_next = 3;
    const Frame after_gap = camera->grab(1s).value();
    EXPECT_EQ(after_gap.frame_id, 4u);
    EXPECT_TRUE(matches_pattern(after_gap, V4L2_PIX_FMT_Y16, 4));
    EXPECT_EQ(camera->statistics().dropped, 3u);
}

TEST(V4l2Camera, ThirtyTwoBitSequenceWrapKeepsIdsMonotonic) {
    auto device = std::make_shared<FakeV4l2Device>();
    device->next_sequence = 0xFFFFFFFEu;
    auto camera = open_fake(device);
    ASSERT_TRUE(camera);
    ASSERT_TRUE(camera->start().ok());
    std::uint64_t previous = 0;
    for (int i = 0; i < 4; ++i) {
        const Frame f = camera->grab(1s).value();
        if (i > 0) {
            EXPECT_EQ(f.frame_id, previous + 1);
        }
        previous = f.frame_id;
    }
    EXPECT_EQ(previous, 0x100000001u);
    EXPECT_EQ(camera->statistics().dropped, 0u);
}

TEST(V4l2Camera, SpuriousWakeupIsRetriedAndAStalledSensorTimesOut) {
    auto device = std::make_shared<FakeV4l2Device>();
    auto camera = open_fake(device);
    ASSERT_TRUE(camera);
    ASSERT_TRUE(camera->start().ok());
    device->spurious_wakeup_next = true;  // POLLIN, then DQBUF says EAGAIN
    ASSERT_TRUE(camera->grab(1s).ok());
    device->frames_left = 0;
    const auto timed_out = camera->grab(50ms);
    ASSERT_FALSE(timed_out.ok());
    EXPECT_EQ(timed_out.error().code, DeviceErrorCode::Timeout);
}

TEST(V4l2Camera, CorruptedAndShortBuffersAreIncompleteAndRequeued) {
    auto device = std::make_shared<FakeV4l2Device>();
    auto camera = open_fake(device);
    ASSERT_TRUE(camera);
    ASSERT_TRUE(camera->start().ok());
    device->corrupt_next = true;
    Frame f = camera->grab(1s).value();
    EXPECT_EQ(f.frame_id, 1u);  // frame 0 carried V4L2_BUF_FLAG_ERROR
    device->short_next = true;
    f = camera->grab(1s).value();
    EXPECT_EQ(f.frame_id, 3u);  // frame 2 had half its bytes
    const StreamStatistics stats = camera->statistics();
    EXPECT_EQ(stats.incomplete, 2u);
    EXPECT_EQ(stats.delivered, 2u);
    EXPECT_EQ(stats.dropped, 0u);
    EXPECT_EQ(device->queued_count(), 4u);
}

TEST(V4l2Camera, UnsupportedFormatsAreRefused) {
    {
        auto device = std::make_shared<FakeV4l2Device>();
        V4l2CameraOptions options;
        options.pixel_format = "YUYV";
        const auto camera = open_v4l2_camera("/dev/video0", options, device);
        ASSERT_FALSE(camera.ok());
        EXPECT_EQ(camera.error().code, DeviceErrorCode::InvalidArgument);
    }
    for (bool einval : {true, false}) {
        auto device = std::make_shared<FakeV4l2Device>();
        device->formats = {{V4L2_PIX_FMT_GREY, 80, 60}};
        device->refuse_unsupported_with_einval = einval;
        V4l2CameraOptions options;
        options.pixel_format = "Y16";
        const auto camera = open_v4l2_camera("/dev/video0", options, device);
        ASSERT_FALSE(camera.ok());
        EXPECT_EQ(camera.error().code, DeviceErrorCode::NotSupported) << camera.error().message;
        EXPECT_NE(camera.error().message.find("Y16"), std::string::npos) << camera.error().message;
    }
    {
        auto device = std::make_shared<FakeV4l2Device>();
        V4l2CameraOptions options;
        options.width = 640;  // the core has one discrete size: the driver adjusts it to 160×120
        const auto camera = open_v4l2_camera("/dev/video0", options, device);
        ASSERT_FALSE(camera.ok());
        EXPECT_EQ(camera.error().code, DeviceErrorCode::NotSupported);
    }
}

TEST(V4l2Camera, UnpluggedDeviceIsDisconnected) {
    auto device = std::make_shared<FakeV4l2Device>();
    auto camera = open_fake(device);
    ASSERT_TRUE(camera);
    ASSERT_TRUE(camera->start().ok());
    ASSERT_TRUE(camera->grab(1s).ok());
    device->unplugged = true;
    const auto frame = camera->grab(1s);
    ASSERT_FALSE(frame.ok());
    EXPECT_EQ(frame.error().code, DeviceErrorCode::Disconnected);

    const auto absent = open_v4l2_camera("/dev/video7", {}, std::make_shared<FakeV4l2Device>());
    ASSERT_FALSE(absent.ok());
    EXPECT_EQ(absent.error().code, DeviceErrorCode::Disconnected);
    EXPECT_NE(absent.error().message.find("/dev/video7"), std::string::npos);
}

TEST(FakeV4l2Device, EnforcesTheBufferQueueRules) {
    // The fake is only useful if it refuses what a driver refuses (kernel docs, VIDIOC_QBUF/DQBUF,
    // REQBUFS).
    FakeV4l2Device device;
    const int fd = device.open("/dev/video0", O_RDWR | O_NONBLOCK);
    ASSERT_GE(fd, 0);
    int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    EXPECT_EQ(device.ioctl(fd, VIDIOC_STREAMON, &type), -1);  // no buffers yet
    EXPECT_EQ(errno, EINVAL);
    v4l2_requestbuffers req{};
    req.count = 2;
    req.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    req.memory = V4L2_MEMORY_USERPTR;
    EXPECT_EQ(device.ioctl(fd, VIDIOC_REQBUFS, &req), -1);  // only MMAP
    req.memory = V4L2_MEMORY_MMAP;
    ASSERT_EQ(device.ioctl(fd, VIDIOC_REQBUFS, &req), 0);
    v4l2_buffer buf{};
    buf.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    buf.memory = V4L2_MEMORY_MMAP;
    buf.index = 0;
    ASSERT_EQ(device.ioctl(fd, VIDIOC_QBUF, &buf), 0);
    EXPECT_EQ(device.ioctl(fd, VIDIOC_QBUF, &buf), -1);  // already queued
    EXPECT_EQ(errno, EINVAL);
    buf.index = 2;
    EXPECT_EQ(device.ioctl(fd, VIDIOC_QBUF, &buf), -1);   // no such buffer
    EXPECT_EQ(device.ioctl(fd, VIDIOC_DQBUF, &buf), -1);  // not streaming
    ASSERT_EQ(device.ioctl(fd, VIDIOC_STREAMON, &type), 0);
    EXPECT_EQ(device.ioctl(fd, VIDIOC_DQBUF, &buf), -1);  // nothing done yet, non-blocking
    EXPECT_EQ(errno, EAGAIN);
    EXPECT_EQ(device.ioctl(fd, VIDIOC_REQBUFS, &req), -1);  // busy while streaming
    EXPECT_EQ(errno, EBUSY);
    v4l2_format fmt{};
    fmt.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    EXPECT_EQ(device.ioctl(fd, VIDIOC_S_FMT, &fmt), -1);  // busy while buffers exist
    EXPECT_EQ(errno, EBUSY);
    EXPECT_EQ(device.ioctl(fd, 0xDEAD, &fmt), -1);
    EXPECT_EQ(errno, ENOTTY);
}

/// Test double at the seam V4L2 cannot be real here: a stage whose move lasts 80 ms while the
/// camera's sensor keeps filling the queued buffers (a Boson does not stop for the mount).
class StageFillingTheQueue final : public Stage {
public:
    explicit StageFillingTheQueue(FakeV4l2Device& device) : m_device(device) {}
    StageInfo info() const override { return {"fill://", "test", "queue filler", "0", "0", 100.0}; }
    Status home(std::chrono::milliseconds) override { return ok_status(); }
    bool is_homed() const override { return true; }
    Status move_absolute(double angle_deg, std::chrono::milliseconds) override {
        for (int i = 0; i < 8; ++i) {
            m_device.expose_frame_now();
            std::this_thread::sleep_for(10ms);
        }
        m_angle = angle_deg;
        last_sequence_during_move = m_device.next_sequence - 1;
        return ok_status();
    }
    Result<double> position_deg() override { return m_angle; }
    std::uint32_t last_sequence_during_move = 0;

private:
    FakeV4l2Device& m_device;
    double m_angle = 0;
};

// `frames` frames at one angle, 0°, after a 20 ms settle, recorded as a session in `dir`.
CaptureSummary capture_one_angle(Camera& camera, StageFillingTheQueue& stage, int frames,
                                 const std::filesystem::path& dir) {
    CapturePlan plan;
    plan.angles_deg = {0.0};
    plan.frames_per_angle = frames;
    plan.settle_s = 0.02;
    auto session =
        SessionWriter::create(dir, new_session_manifest(camera.info(), stage.info(), plan));
    CaptureOptions capture_options;
    capture_options.progress_stream = nullptr;
    return run_capture(camera, stage, plan, session, capture_options);
}

TEST(V4l2Camera, CaptureDiscardsBuffersFilledDuringTheMove) {
    // Four mmap buffers fill during the move; DQBUF hands them out first. Their driver timestamps
    // (CLOCK_MONOTONIC at fill, mapped to CLOCK_REALTIME) predate the settle end, so the capture
    // loop discards them however late they are dequeued; the kept frames' pattern says which they
    // were.
    auto device = std::make_shared<FakeV4l2Device>();
    device->stamp_with_monotonic_clock = true;
    V4l2CameraOptions options;
    options.pixel_format = "Y16";
    options.frame_rate_hz = 60.0;
    auto camera = open_fake(device, options);
    ASSERT_TRUE(camera);
    StageFillingTheQueue stage(*device);
    test::TempDir tmp;
    const auto summary = capture_one_angle(*camera, stage, 3, tmp / "s");
    EXPECT_GE(summary.stale_discarded, 4u);  // the four buffers filled during the move, at least

    const SessionManifest m = read_session(tmp / "s");
    ASSERT_EQ(m.records.size(), 1u);
    const SessionRecord& r = m.records[0];
    ASSERT_TRUE(r.timing);
    EXPECT_EQ(r.timing->stale_frames_discarded, static_cast<std::int64_t>(summary.stale_discarded));
    EXPECT_EQ(r.timing->exposure_window_ns, 25'000'000);  // 1.5 / 60 Hz
    EXPECT_GE(r.first_timestamp_ns - r.timing->exposure_window_ns, r.timing->settle_end_ns);
    // Y16 pattern at pixel (0, 0) is 7 × sequence: the mean of the kept frames' sequences.
    const Image mean = read_session_frame(tmp / "s", m, r);
    EXPECT_GT(mean.channel("counts")[0] / 7.0,
              static_cast<double>(stage.last_sequence_during_move));
}

TEST(V4l2Camera, DeclaredMicrogridPatternIsReportedAndRecordedInTheSession) {
    // A microgrid camera on V4L2 streams plain Y16; its pattern (here the Sony layout mirrored in
    // x, as a ReverseX readout gives) is declared and must reach the session manifest, where
    // reduction reads it.
    auto device = std::make_shared<FakeV4l2Device>();
    device->stamp_with_monotonic_clock = true;  // driver timestamps on the host's clock
    EXPECT_FALSE(open_fake(device)->info().microgrid_pattern_deg);  // not declared: none
    V4l2CameraOptions options;
    options.pixel_format = "Y16";
    options.microgrid_pattern_deg = std::array<double, 4>{45.0, 90.0, 0.0, 135.0};
    auto camera = open_fake(device, options);
    ASSERT_TRUE(camera);
    ASSERT_TRUE(camera->info().microgrid_pattern_deg);
    EXPECT_EQ(*camera->info().microgrid_pattern_deg, *options.microgrid_pattern_deg);
    StageFillingTheQueue stage(*device);
    test::TempDir tmp;
    capture_one_angle(*camera, stage, 2, tmp / "s");
    const SessionManifest m = read_session(tmp / "s");
    ASSERT_EQ(m.records.size(), 1u);
    ASSERT_TRUE(m.camera.microgrid_pattern_deg);
    EXPECT_EQ(*m.camera.microgrid_pattern_deg, *options.microgrid_pattern_deg);
}

TEST(CameraRegistry, V4l2MicrogridKeyIsParsedAndCheckedBeforeTheDeviceIsOpened) {
    const std::string bad = test::open_camera_error("v4l2:///dev/video0?microgrid=0,45,90");
    EXPECT_NE(bad.find("microgrid"), std::string::npos) << bad;
    EXPECT_NE(test::open_camera_error("v4l2:///dev/video0?microgrid=0,45,90,200").find("200"),
              std::string::npos);
    // A valid pattern is accepted: what fails then is the absent device, as a device error.
    const auto camera = open_camera("v4l2:///dev/tirpol-no-such-video?microgrid=sony");
    ASSERT_FALSE(camera.ok());
    EXPECT_EQ(camera.error().code, DeviceErrorCode::Disconnected);
}

TEST(CameraRegistry, V4l2UrisAreCheckedAndAnAbsentDeviceIsADeviceError) {
    EXPECT_NE(test::open_camera_error("v4l2://video0").find("absolute device path"),
              std::string::npos);
    EXPECT_NE(test::open_camera_error("v4l2:///dev/video0?buffers=1").find("buffers=1"),
              std::string::npos);
    const auto camera = open_camera("v4l2:///dev/tirpol-no-such-video");
    ASSERT_FALSE(camera.ok());
    EXPECT_EQ(camera.error().code, DeviceErrorCode::Disconnected);
}

}  // namespace
}  // namespace tirpol::acquisition
