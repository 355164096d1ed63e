// Requires TIRPOL_WITH_ARAVIS (built only with that back end: cmake/TirpolBackends.cmake).
// FakeGigECameraServer: Aravis's GigE Vision fake camera served in-process with a C++ fill
// callback; the aravis:// camera receives, over real GVCP/GVSP on loopback, exactly the counts the
// callback wrote.

#include <gtest/gtest.h>

#include <atomic>

#include "fake_gv_camera_process.h"
#include "test_support.h"
#include "tirpol/acquisition/internal/aravis_camera.h"
#include "tirpol/acquisition/sim/fake_gige_server.h"
#include "tirpol/core/error.h"

namespace tirpol::acquisition {
namespace {

using namespace std::chrono_literals;

float pattern(int x, int y, std::uint64_t frame_id) {
    return static_cast<float>(1000 + x + 10 * y + static_cast<int>(frame_id % 100));
}

FakeGigECameraOptions thermal_options() {
    FakeGigECameraOptions o;
    o.genicam_xml = test::source_dir() / "tests/data/genicam/thermal-fake-camera.xml";
    return o;
}

TEST(FakeGigECameraServer, ServesTheCountsItsCallbackWritesInMono14) {
    test::LoopbackGigELock lock;
    FakeGigECameraServer server(thermal_options());
    std::atomic<int> calls{0};
    std::atomic<bool> request_ok{true};
    server.set_fill([&](const FakeGigEFrameRequest& r, std::vector<float>& counts) {
        ++calls;
        if (r.pixel_format != "Mono14" || r.bits_per_pixel != 14 || counts.size() != 64u * 48u)
            request_ok = false;
        for (int y = 0; y < r.height; ++y)
            for (int x = 0; x < r.width; ++x)
                counts[static_cast<std::size_t>(y * r.width + x)] = pattern(x, y, r.frame_id);
    });
    AravisCameraOptions options;
    options.pixel_format = "Mono14";
    options.width = 64;
    options.height = 48;
    options.frame_rate_hz = 100.0;
    auto opened = open_aravis_camera(server.device_id(), options);
    ASSERT_TRUE(opened.ok()) << opened.error().message;
    Camera& camera = *opened.value();
    EXPECT_EQ(camera.info().bits_per_pixel, 14);
    ASSERT_TRUE(camera.start().ok());
    for (int i = 0; i < 5; ++i) {
        auto frame = camera.grab(2s);
        ASSERT_TRUE(frame.ok()) << frame.error().message;
        const Frame& f = frame.value();
        ASSERT_EQ(f.counts.size(), 64u * 48u);
        const std::uint64_t raw_id = (f.frame_id - 1) % 65535 + 1;
        for (int y = 0; y < 48; ++y)
            for (int x = 0; x < 64; ++x)
                ASSERT_EQ(f.counts[static_cast<std::size_t>(y * 64 + x)], pattern(x, y, raw_id))
                    << x << "," << y;
    }
    ASSERT_TRUE(camera.stop().ok());
    EXPECT_GE(calls.load(), 5);
    EXPECT_TRUE(request_ok.load());
}

TEST(FakeGigECameraServer, ClipsToTheFormatRangeAndRestoresAravisPattern) {
    test::LoopbackGigELock lock;
    FakeGigECameraServer server;  // Aravis's built-in XML: Mono8 and Mono16
    server.set_fill([](const FakeGigEFrameRequest&, std::vector<float>& counts) {
        for (std::size_t i = 0; i < counts.size(); ++i) counts[i] = (i % 2 == 0) ? 1e6f : -5.0f;
    });
    AravisCameraOptions options;
    options.pixel_format = "Mono8";
    options.width = 16;
    options.height = 8;
    options.frame_rate_hz = 100.0;
    auto opened = open_aravis_camera(server.device_id(), options);
    ASSERT_TRUE(opened.ok()) << opened.error().message;
    Camera& camera = *opened.value();
    ASSERT_TRUE(camera.start().ok());
    const Frame clipped = camera.grab(2s).value();
    for (std::size_t i = 0; i < clipped.counts.size(); ++i)
        ASSERT_EQ(clipped.counts[i], i % 2 == 0 ? 255.0f : 0.0f);
    ASSERT_TRUE(camera.stop().ok());

    // An empty fill restores arv_fake_camera_diagonal_ramp: Mono8 pixel (x, y) = (x + id + y) mod
    // 255.
    server.set_fill({});
    ASSERT_TRUE(camera.start().ok());
    const Frame ramp = camera.grab(2s).value();
    const std::uint64_t raw_id = (ramp.frame_id - 1) % 65535 + 1;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x)
            ASSERT_EQ(ramp.counts[static_cast<std::size_t>(y * 16 + x)],
                      static_cast<float>((static_cast<std::uint64_t>(x + y) + raw_id) % 255));
}

TEST(FakeGigECameraServer, UnknownInterfaceIsAnErrorNamingIt) {
    FakeGigECameraOptions o;
    o.interface = "tirpol-no-such-if0";
    try {
        FakeGigECameraServer server(o);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("tirpol-no-such-if0"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace tirpol::acquisition
