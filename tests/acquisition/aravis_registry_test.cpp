// Requires TIRPOL_WITH_ARAVIS (built only with that back end: cmake/TirpolBackends.cmake).
// list_cameras() finds Aravis's fake GigE Vision camera through discovery and open_camera opens it
// by its aravis:// URI with the query's options applied (built only with Aravis,
// TIRPOL_WITH_ARAVIS).

#include <gtest/gtest.h>

#include <algorithm>

#include "fake_gv_camera_process.h"
#include "open_camera_error.h"
#include "tirpol/acquisition/camera.h"
#include "tirpol/core/error.h"

namespace tirpol::acquisition {
namespace {

using namespace std::chrono_literals;

using test::open_camera_error;

TEST(CameraRegistry, MalformedAravisUrisThrowNamingTheKey) {
    EXPECT_NE(open_camera_error("aravis://X?exposure=10").find("exposure"), std::string::npos);
    EXPECT_NE(open_camera_error("aravis://X?trigger=hardware").find("trigger=hardware"),
              std::string::npos);
}

TEST(CameraRegistry, ListsAndOpensTheFakeGigECameraByUri) {
    const auto binary = test::find_fake_gv_camera_binary();
    if (!binary)
        FAIL() << test::kFakeGvCameraBinary
               << " not found on PATH: install the Debian package aravis-tools (./run does)";
    test::LoopbackGigELock lock;
    test::FakeGvCameraProcess fake(*binary, {});
    ASSERT_TRUE(fake.ready());
    const auto cameras = list_cameras();
    const std::string uri = std::string("aravis://") + test::kFakeGvCameraId;
    const auto it = std::find_if(cameras.begin(), cameras.end(),
                                 [&](const CameraDescriptor& c) { return c.uri == uri; });
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
