// open_camera(uri) dispatches on the scheme and turns the query into options. The aravis:// and
// v4l2:// URIs are tested in aravis_registry_test.cpp and v4l2_camera_test.cpp, built with their
// back end.

#include <gtest/gtest.h>

#include "open_camera_error.h"
#include "tirpol/acquisition/camera.h"
#include "tirpol/core/error.h"

namespace tirpol::acquisition {
namespace {

using namespace std::chrono_literals;

using test::open_camera_error;

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
    EXPECT_NE(open_camera_error("gige://cam").find("unknown camera scheme 'gige'"),
              std::string::npos);
    EXPECT_NE(open_camera_error("camera0").find("<scheme>://"), std::string::npos);
    EXPECT_NE(open_camera_error("sim://uniform?exposure=10").find("exposure"), std::string::npos);
}

}  // namespace
}  // namespace tirpol::acquisition
