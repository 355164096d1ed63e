// open_camera(uri) dispatches on the scheme and turns the query into options; list_cameras() finds
// the fake GigE Vision camera through Aravis discovery.

#include <gtest/gtest.h>

#include "fake_gv_camera_process.h"
#include "tirpol/acquisition/camera_registry.h"
#include "tirpol/core/error.h"

namespace tirpol::acquisition {
namespace {

using namespace std::chrono_literals;

std::string error_text(const std::string& uri) {
    try {
        (void)open_camera(uri);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(CameraRegistry, SimUriBuildsAUniformCamera) {
    auto camera = open_camera("sim://uniform?width=4&height=3&counts=1234&fps=25");
    ASSERT_TRUE(camera.ok());
    ASSERT_TRUE(camera.value()->start().ok());
    const Frame frame = camera.value()->grab(1s).value();
    EXPECT_EQ(frame.width, 4);
    EXPECT_EQ(frame.height, 3);
    for (float v : frame.counts) EXPECT_EQ(v, 1234.0f);
    EXPECT_EQ(camera.value()->info().frame_rate_hz, 25.0);
}

TEST(CameraRegistry, MalformedUrisThrowNamingTheProblem) {
    EXPECT_NE(error_text("gige://cam").find("unknown camera scheme 'gige'"), std::string::npos);
    EXPECT_NE(error_text("camera0").find("<scheme>://"), std::string::npos);
    EXPECT_NE(error_text("aravis://X?exposure=10").find("exposure"), std::string::npos);
    EXPECT_NE(error_text("aravis://X?trigger=hardware").find("trigger=hardware"), std::string::npos);
    EXPECT_NE(error_text("v4l2://video0").find("absolute device path"), std::string::npos);
    EXPECT_NE(error_text("v4l2:///dev/video0?buffers=1").find("buffers=1"), std::string::npos);
}

TEST(CameraRegistry, AbsentV4l2DeviceIsADeviceError) {
    const auto camera = open_camera("v4l2:///dev/tirpol-no-such-video");
    ASSERT_FALSE(camera.ok());
    EXPECT_EQ(camera.error().code, DeviceErrorCode::Disconnected);
}

TEST(CameraRegistry, ListsAndOpensTheFakeGigECameraByUri) {
    const auto binary = test::find_fake_gv_camera_binary();
    if (!binary) FAIL() << test::kFakeGvCameraBinary << " not found on PATH: install the Debian package aravis-tools (./run does)";
    test::LoopbackGigELock lock;
    test::FakeGvCameraProcess fake(*binary, {});
    ASSERT_TRUE(fake.ready());
    const auto cameras = list_cameras();
    const std::string uri = std::string("aravis://") + test::kFakeGvCameraId;
    const auto it = std::find_if(cameras.begin(), cameras.end(), [&](const CameraDescriptor& c) { return c.uri == uri; });
    ASSERT_NE(it, cameras.end());
    EXPECT_NE(it->description.find("127.0.0.1"), std::string::npos) << it->description;

    auto camera = open_camera(uri + "?pixel_format=Mono16&width=32&height=16&fps=100&buffers=8");
    ASSERT_TRUE(camera.ok()) << camera.error().message;
    const CameraInfo info = camera.value()->info();
    EXPECT_EQ(info.pixel_format, "Mono16");
    EXPECT_EQ(info.width, 32);
    EXPECT_EQ(info.height, 16);
    EXPECT_EQ(info.frame_rate_hz, 100.0);
    ASSERT_TRUE(camera.value()->start().ok());
    EXPECT_TRUE(camera.value()->grab(2s).ok());
}

}  // namespace
}  // namespace tirpol::acquisition
