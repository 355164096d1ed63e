// One parser of device URIs: camera factories (parse_device_uri, which throws) and stage and
// blackbody factories (split_device_uri, errors as values) read the same scheme, target and query
// from the same text and report a bad URI with the same message.

#include "tirpol/acquisition/device_uri.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace tirpol::acquisition {
namespace {

using testing::HasSubstr;

TEST(DeviceUri, SplitsSchemeTargetAndQuery) {
    const DeviceUri u =
        parse_device_uri("thorlabs-apt+usb://55000123?counts_per_degree=1000&channel=1");
    EXPECT_EQ(u.scheme, "thorlabs-apt+usb");
    EXPECT_EQ(u.target, "55000123");
    EXPECT_EQ(u.query, (std::map<std::string, std::string>{{"counts_per_degree", "1000"},
                                                           {"channel", "1"}}));
    EXPECT_EQ(u.integer("channel", 0), 1);
    EXPECT_EQ(u.number("counts_per_degree", 0.0), 1000.0);
}

TEST(DeviceUri, ValueAndThrowingParsersReadTheSameFields) {
    for (const std::string uri :
         {"sim://", "elliptec:///dev/ttyUSB0?address=0", "aravis://Fake?exposure_us=500&"}) {
        const DeviceUri camera = parse_device_uri(uri);
        const auto stage = split_device_uri(uri);
        ASSERT_TRUE(stage) << uri << ": " << stage.error().message;
        EXPECT_EQ(stage.value().scheme, camera.scheme) << uri;
        EXPECT_EQ(stage.value().target, camera.target) << uri;
        EXPECT_EQ(stage.value().query, camera.query) << uri;
    }
}

TEST(DeviceUri, EmptyQueryItemsAreSkipped) {
    const auto u = split_device_uri("sim://x?a=1&&b=2&");
    ASSERT_TRUE(u) << u.error().message;
    EXPECT_EQ(u.value().query, (std::map<std::string, std::string>{{"a", "1"}, {"b", "2"}}));
}

TEST(DeviceUri, BadUriIsAValueForStagesAndAnErrorForCamerasWithOneMessage) {
    for (const auto& [uri, expected] : std::vector<std::pair<std::string, std::string>>{
             {"/dev/ttyUSB0", "expected <scheme>://<target>"},
             {"://x", "expected <scheme>://<target>"},
             {"sim://x?a=1&speed", "query item 'speed' is not key=value"},
             {"sim://x?=3", "query item '=3' is not key=value"}}) {
        const auto stage = split_device_uri(uri);
        ASSERT_FALSE(stage) << uri;
        EXPECT_EQ(stage.error().code, DeviceErrorCode::InvalidArgument);
        EXPECT_THAT(stage.error().message, HasSubstr("device URI '" + uri + "': " + expected));
        try {
            parse_device_uri(uri);
            ADD_FAILURE() << uri << ": expected tirpol::Error";
        } catch (const Error& e) {
            EXPECT_EQ(std::string(e.what()), stage.error().message);
        }
    }
}

}  // namespace
}  // namespace tirpol::acquisition
