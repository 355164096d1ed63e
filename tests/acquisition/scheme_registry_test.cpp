// register_camera_scheme / register_stage_scheme: a plug-in's scheme opens through the ordinary
// open_camera / open_stage, a replaced factory is handed back so the plug-in can pass URIs on, and
// an unknown scheme's error lists what is registered.

#include <gtest/gtest.h>

#include <chrono>

#include "open_camera_error.h"
#include "tirpol/acquisition/camera.h"
#include "tirpol/acquisition/device_uri.h"
#include "tirpol/acquisition/internal/sim_stage.h"
#include "tirpol/acquisition/sim/simulated_camera.h"
#include "tirpol/acquisition/stage.h"
#include "tirpol/core/error.h"

namespace tirpol::acquisition {
namespace {

using namespace std::chrono_literals;

using test::open_camera_error;

bool contains(const std::vector<std::string>& names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
}

TEST(CameraSchemes, BuiltInSchemesAreRegistered) {
    const auto schemes = camera_schemes();
    EXPECT_TRUE(contains(schemes, "sim"));
    EXPECT_TRUE(std::is_sorted(schemes.begin(), schemes.end()));
}

TEST(CameraSchemes, PluggedInSchemeOpensThroughOpenCamera) {
    // A constant-counts camera as a plug-in would register it: its own scheme, its own query key.
    const CameraFactory previous =
        register_camera_scheme("test-constant", [](const std::string& uri) {
            const DeviceUri u = parse_device_uri(uri);
            u.check_keys({"counts"});
            SimulatedCameraConfig config;
            config.width = 3;
            config.height = 2;
            const auto counts = static_cast<float>(u.number("counts", 0.0));
            return Result<std::unique_ptr<Camera>>(std::make_unique<SimulatedCamera>(
                config, [counts](double, std::vector<float>& out) {
                    std::fill(out.begin(), out.end(), counts);
                }));
        });
    EXPECT_FALSE(previous);  // a new scheme replaces nothing
    EXPECT_TRUE(contains(camera_schemes(), "test-constant"));

    auto camera = open_camera("test-constant://x?counts=321");
    ASSERT_TRUE(camera.ok());
    ASSERT_TRUE(camera.value()->start().ok());
    const Frame frame = camera.value()->grab(2s).value();
    ASSERT_EQ(frame.counts.size(), 6u);
    for (float v : frame.counts) EXPECT_EQ(v, 321.0f);
    EXPECT_NE(open_camera_error("test-constant://x?gain=2").find("unknown query key 'gain'"),
              std::string::npos);
}

TEST(CameraSchemes, ReplacingASchemeHandsBackThePreviousFactory) {
    int chained_calls = 0;
    register_camera_scheme("test-chain", [](const std::string&) -> Result<std::unique_ptr<Camera>> {
        return DeviceError{DeviceErrorCode::NotSupported, "first factory"};
    });
    auto first = std::make_shared<CameraFactory>();
    *first = register_camera_scheme("test-chain", [first, &chained_calls](const std::string& uri) {
        ++chained_calls;
        return (*first)(uri);
    });
    ASSERT_TRUE(*first);
    const auto camera = open_camera("test-chain://anything");
    ASSERT_FALSE(camera.ok());
    EXPECT_EQ(camera.error().message, "first factory");
    EXPECT_EQ(chained_calls, 1);
}

TEST(CameraSchemes, UnknownSchemeListsTheRegisteredOnes) {
    const std::string message = open_camera_error("gige://cam");
    EXPECT_NE(message.find("unknown camera scheme 'gige'"), std::string::npos) << message;
    for (const std::string& scheme : camera_schemes())
        EXPECT_NE(message.find(scheme), std::string::npos) << scheme;
}

TEST(CameraSchemes, RejectsNamesThatAreNotSchemes) {
    const CameraFactory any = [](const std::string&) -> Result<std::unique_ptr<Camera>> {
        return DeviceError{DeviceErrorCode::NotSupported, "unused"};
    };
    EXPECT_THROW(register_camera_scheme("", any), Error);
    EXPECT_THROW(register_camera_scheme("a://b", any), Error);
    EXPECT_THROW(register_camera_scheme("ok", CameraFactory{}), Error);
}

TEST(StageSchemes, PluggedInSchemeOpensThroughOpenStage) {
    register_stage_scheme("test-stage",
                          [](const std::string& uri) -> Result<std::unique_ptr<Stage>> {
                              return make_simulated_stage(uri, SimulatedStageOptions{});
                          });
    auto stage = open_stage("test-stage://mount");
    ASSERT_TRUE(stage.ok()) << stage.error().message;
    ASSERT_TRUE(stage.value()->home(2s).ok());
    ASSERT_TRUE(stage.value()->move_absolute(30.0, 5s).ok());
    EXPECT_NEAR(stage.value()->position_deg().value(), 30.0, 0.05);
    EXPECT_EQ(stage.value()->info().uri, "test-stage://mount");
}

TEST(StageSchemes, UnknownSchemeIsInvalidArgumentListingTheRegisteredOnes) {
    const auto stage = open_stage("newport://x");
    ASSERT_FALSE(stage.ok());
    EXPECT_EQ(stage.error().code, DeviceErrorCode::InvalidArgument);
    const auto schemes = stage_schemes();
    for (const char* built_in : {"thorlabs-apt", "elliptec", "sim"})
        EXPECT_TRUE(contains(schemes, built_in)) << built_in;
    for (const std::string& scheme : schemes)
        EXPECT_NE(stage.error().message.find(scheme), std::string::npos) << stage.error().message;
}

// The build's back ends (cmake/TirpolBackends.cmake; acquisition/CMakeLists.txt passes them to this
// file as 0/1) and the registries agree: a back end that is off registers no scheme, so its URIs
// fail as an unknown scheme that lists what is there, and one that is on is registered.
TEST(BackEndSchemes, RegisteredExactlyWhenTheBackEndIsBuilt) {
    EXPECT_EQ(contains(camera_schemes(), "aravis"), TIRPOL_TEST_HAVE_ARAVIS == 1);
    EXPECT_EQ(contains(camera_schemes(), "v4l2"), TIRPOL_TEST_HAVE_V4L2 == 1);
    EXPECT_EQ(contains(stage_schemes(), "thorlabs-apt+usb"), TIRPOL_TEST_HAVE_LIBUSB == 1);
    if (TIRPOL_TEST_HAVE_ARAVIS == 0) {
        const std::string message = open_camera_error("aravis://Fake");
        EXPECT_NE(message.find("unknown camera scheme 'aravis'"), std::string::npos) << message;
    }
}

}  // namespace
}  // namespace tirpol::acquisition
