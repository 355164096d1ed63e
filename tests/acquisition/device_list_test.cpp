// `tirpol devices`' library side: serial-port discovery in a /dev-like folder (stable by-id names
// first, the nodes they name not listed twice) and the list's formats.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test_support.h"
#include "tirpol/acquisition/camera.h"

namespace tirpol::acquisition {
namespace {

using ::testing::HasSubstr;

TEST(DeviceList, ByIdLinksComeFirstAndTheirNodesAreNotListedTwice) {
    const test::TempDir dev("device_list");
    for (const char* node : {"ttyUSB1", "ttyUSB0", "ttyACM0", "ttyS0", "video0"})
        test::write_text(dev / node, "");
    std::filesystem::create_directories(dev / "serial/by-id");
    std::filesystem::create_symlink("../../ttyUSB1", dev / "serial/by-id/usb-FTDI_K-Cube_83-if00");
    const auto ports = list_serial_ports(dev.path());
    ASSERT_EQ(ports.size(), 3u);
    EXPECT_EQ(ports[0].path, (dev / "serial/by-id/usb-FTDI_K-Cube_83-if00").string());
    EXPECT_EQ(ports[0].device, std::filesystem::weakly_canonical(dev / "ttyUSB1").string());
    EXPECT_EQ(ports[1].path, (dev / "ttyACM0").string());
    EXPECT_EQ(ports[2].path, (dev / "ttyUSB0").string());
    EXPECT_EQ(ports[2].device, ports[2].path);
}

TEST(DeviceList, NoPortsInAFolderWithoutSerialNodes) {
    const test::TempDir dev("device_list_empty");
    EXPECT_TRUE(list_serial_ports(dev.path()).empty());
}

TEST(DeviceList, FormatsListBothKindsAndSayWhenNoneWasFound) {
    const DeviceList none;
    const std::string empty = device_list_text(none);
    EXPECT_THAT(empty, HasSubstr("(none found: no GigE Vision"));
    EXPECT_THAT(empty, HasSubstr("(none found under /dev/serial/by-id"));
    const nlohmann::json j0 = device_list_json(none);
    EXPECT_TRUE(j0["cameras"].is_array() && j0["cameras"].empty());
    EXPECT_TRUE(j0["serial_ports"].is_array() && j0["serial_ports"].empty());

    DeviceList some;
    some.cameras.push_back({"v4l2:///dev/video0", "PureThermal"});
    some.serial_ports.push_back({"/dev/serial/by-id/x", "/dev/ttyUSB0"});
    some.serial_ports.push_back({"/dev/ttyACM0", "/dev/ttyACM0"});
    const std::string text = device_list_text(some);
    EXPECT_THAT(text, HasSubstr("  v4l2:///dev/video0" + std::string(22, ' ') + " PureThermal\n"));
    EXPECT_THAT(text, HasSubstr("  /dev/serial/by-id/x -> /dev/ttyUSB0\n"));
    EXPECT_THAT(text, HasSubstr("  /dev/ttyACM0\n"));
    const nlohmann::json j = device_list_json(some);
    EXPECT_EQ(j["cameras"][0]["uri"], "v4l2:///dev/video0");
    EXPECT_EQ(j["serial_ports"][0]["device"], "/dev/ttyUSB0");
}

}  // namespace
}  // namespace tirpol::acquisition
