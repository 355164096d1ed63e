// Thorlabs Elliptec ASCII codec. Source: Thorlabs, "Elliptec ELLx modules protocol manual"
// (Issue 7+): command/reply framing, the `in` reply field layout (as also parsed by the
// roesel/elliptec Python package: type [3:5], serial [5:13], year [13:17], firmware [17:19],
// thread [19], hardware [20], travel [21:25], pulses [25:33]), 8-digit two's-complement positions,
// and the `gs` status table (0 OK ... 9 Busy ... 13 Over current error).

#include "tirpol/acquisition/internal/elliptec_protocol.h"

#include <gtest/gtest.h>

namespace tirpol::acquisition::elliptec {
namespace {

TEST(ElliptecProtocol, CommandsAreAddressPlusLowerCaseMnemonic) {
    EXPECT_EQ(info_request('0'), "0in");
    EXPECT_EQ(home('0'), "0ho0");
    EXPECT_EQ(home('A', false), "Aho1");
    EXPECT_EQ(get_position('0'), "0gp");
    EXPECT_EQ(get_status('2'), "2gs");
    // ELL14: 143360 pulses per 360°, so 90° = 35840 = 0x8C00.
    EXPECT_EQ(move_absolute('0', 35840), "0ma00008C00");
}

TEST(ElliptecProtocol, PositionsAreEightHexDigitsTwosComplement) {
    EXPECT_EQ(encode_position(0), "00000000");
    EXPECT_EQ(encode_position(-1), "FFFFFFFF");
    EXPECT_EQ(encode_position(-35840), "FFFF7400");
    EXPECT_EQ(decode_position("FFFF7400"), -35840);
    EXPECT_EQ(decode_position("00008c00"), 35840);  // the manual's hosts may send lower case
    EXPECT_FALSE(decode_position("8C00"));
    EXPECT_FALSE(decode_position("0000GC00"));
}

TEST(ElliptecProtocol, InfoReplyFieldsAreReadNotAssumed) {
    // "0IN" + type 0E (ELL14) + serial 11400123 + year 2023 + firmware 17 + thread 0 (metric) +
    // hardware 1 + travel 0168 (360) + pulses 00023000 (143360).
    const auto reply = parse_reply("0IN0E1140012320231701016800023000");
    ASSERT_TRUE(reply);
    EXPECT_EQ(reply->address, '0');
    EXPECT_EQ(reply->code, "IN");
    const auto info = parse_info(*reply);
    ASSERT_TRUE(info);
    EXPECT_EQ(info->motor_type, 14);
    EXPECT_EQ(info->serial, "11400123");
    EXPECT_EQ(info->year, "2023");
    EXPECT_EQ(info->firmware, 0x17);
    EXPECT_FALSE(info->imperial_thread);
    EXPECT_EQ(info->hardware_release, 1);
    EXPECT_EQ(info->travel, 360u);
    EXPECT_EQ(info->pulses, 143360u);
    EXPECT_NEAR(info->pulses_per_unit(), 398.2222, 1e-4);
    EXPECT_EQ(encode_info(*info), reply->data);
    // A module with another scaling (e.g. an ELL18 reporting 262144 pulses) is read as such.
    const auto other =
        parse_info(*parse_reply("0IN1211800456202116010168"
                                "00040000"));
    ASSERT_TRUE(other);
    EXPECT_NEAR(other->pulses_per_unit(), 262144.0 / 360.0, 1e-9);
    EXPECT_FALSE(parse_info(*parse_reply("0IN0E11400123")));  // truncated
}

TEST(ElliptecProtocol, StatusCodesHaveTheManualsMeanings) {
    const auto busy = parse_reply("0GS09");
    ASSERT_TRUE(busy);
    EXPECT_EQ(parse_status(*busy), kBusy);
    EXPECT_EQ(status_meaning(kBusy), "Busy");
    EXPECT_EQ(status_meaning(kMechanicalTimeout), "Mechanical time out");
    EXPECT_EQ(status_meaning(kOk), "OK, no error");
    EXPECT_EQ(parse_status(*parse_reply("0GS0C")), kOutOfRange);
    EXPECT_EQ(status_meaning(200), "Reserved status code 200");
    EXPECT_FALSE(parse_status(*parse_reply("0GS9")));
}

TEST(ElliptecProtocol, RepliesAreFramedByCrLf) {
    std::string buffer = "0PO00008C00\r\n0GS0";
    EXPECT_EQ(take_line(buffer), "0PO00008C00");
    EXPECT_FALSE(take_line(buffer));
    buffer += "0\r\n";
    EXPECT_EQ(take_line(buffer), "0GS00");
    EXPECT_TRUE(buffer.empty());
    EXPECT_FALSE(parse_reply("GPO00000000"));  // G is not an address
    EXPECT_FALSE(parse_reply("0po00000000"));  // replies are upper case
}

}  // namespace
}  // namespace tirpol::acquisition::elliptec
