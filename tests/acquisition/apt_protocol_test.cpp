// Thorlabs APT codec against byte sequences from the protocol document.
// Source: Thorlabs, "Thorlabs APT Controllers Host-Controller Communications Protocol", Issue 2x,
// §2.1 message header, and the pages of each message; the same bytes are printed in the README of
// yaq-project/thorlabs-apt-protocol (mot_move_home, mot_move_absolute), which follows the document.

#include "tirpol/acquisition/internal/apt_protocol.h"

#include <gtest/gtest.h>

namespace tirpol::acquisition::apt {
namespace {

using Bytes = std::vector<std::uint8_t>;

TEST(AptProtocol, HeaderOnlyRequestsMatchTheDocument) {
    // "TX 05, 00, 00, 00, 50, 01" — HW_REQ_INFO to the generic USB unit 0x50 from host 0x01.
    EXPECT_EQ(hw_req_info(), (Bytes{0x05, 0x00, 0x00, 0x00, 0x50, 0x01}));
    // MOD_IDENTIFY 0x0223, channel 1 in param1.
    EXPECT_EQ(mod_identify(1), (Bytes{0x23, 0x02, 0x01, 0x00, 0x50, 0x01}));
    // MOT_MOVE_HOME 0x0443 channel 1: b'C\x04\x01\x00P\x01'.
    EXPECT_EQ(mot_move_home(1), (Bytes{0x43, 0x04, 0x01, 0x00, 0x50, 0x01}));
    EXPECT_EQ(mot_req_ustatus_update(1), (Bytes{0x90, 0x04, 0x01, 0x00, 0x50, 0x01}));
    EXPECT_EQ(hw_no_flash_programming(), (Bytes{0x18, 0x00, 0x00, 0x00, 0x50, 0x01}));
    // SET_CHANENABLESTATE: 0x01 enables, 0x02 disables.
    EXPECT_EQ(mod_set_chan_enable_state(1, true), (Bytes{0x10, 0x02, 0x01, 0x01, 0x50, 0x01}));
}

TEST(AptProtocol, MoveAbsoluteSetsTheDataFlagAndLength) {
    // MOT_MOVE_ABSOLUTE channel 1 to 2048 counts: b'S\x04\x06\x00\xd0\x01\x01\x00\x00\x08\x00\x00'
    // — 6-byte data packet, dest 0x50 | 0x80 = 0xD0, channel word, position long, little endian.
    EXPECT_EQ(mot_move_absolute(2048, 1),
              (Bytes{0x53, 0x04, 0x06, 0x00, 0xD0, 0x01, 0x01, 0x00, 0x00, 0x08, 0x00, 0x00}));
    // K10CR1 at 90°: 90 × 409600/3 = 12288000 = 0x00BB8000.
    const auto counts = static_cast<std::int32_t>(90.0 * kK10cr1CountsPerDegree);
    EXPECT_EQ(counts, 12288000);
    EXPECT_EQ(mot_move_absolute(counts),
              (Bytes{0x53, 0x04, 0x06, 0x00, 0xD0, 0x01, 0x01, 0x00, 0x00, 0x80, 0xBB, 0x00}));
    // Negative positions are two's complement longs.
    EXPECT_EQ(mot_move_absolute(-1),
              (Bytes{0x53, 0x04, 0x06, 0x00, 0xD0, 0x01, 0x01, 0x00, 0xFF, 0xFF, 0xFF, 0xFF}));
}

TEST(AptProtocol, DecodesMoveHomedAndMoveCompletedFromTheController) {
    // MOVE_HOMED from the controller (0x50) to the host (0x01): 44 04 01 00 01 50.
    const Bytes homed{0x44, 0x04, 0x01, 0x00, 0x01, 0x50};
    auto d = decode(homed);
    ASSERT_EQ(d.status, DecodeStatus::Complete);
    EXPECT_EQ(d.consumed, 6u);
    EXPECT_EQ(d.message.id, kMotMoveHomed);
    EXPECT_EQ(d.message.param1, 1);
    EXPECT_EQ(d.message.dest, kHostAddress);
    EXPECT_EQ(d.message.source, kUsbDeviceAddress);

    // MOVE_COMPLETED 0x0464 with its 14-byte status: channel 1, position 12288000, velocity 0,
    // current 0, status bits homed | channel enabled.
    const Bytes completed{0x64, 0x04, 0x0E, 0x00, 0x81, 0x50, 0x01, 0x00, 0x00, 0x80,
                          0xBB, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x04, 0x00, 0x80};
    d = decode(completed);
    ASSERT_EQ(d.status, DecodeStatus::Complete);
    EXPECT_EQ(d.consumed, completed.size());
    const auto s = parse_status_update(d.message);
    ASSERT_TRUE(s);
    EXPECT_EQ(s->channel, 1);
    EXPECT_EQ(s->position, 12288000);
    EXPECT_EQ(s->status_bits, kHomed | kChannelEnabled);
    EXPECT_EQ(status_message(kMotMoveCompleted, *s), completed);  // encoder and decoder agree
}

TEST(AptProtocol, StreamDecodingWaitsForWholeMessagesAndResynchronises) {
    const Bytes completed = status_message(kMotMoveCompleted, StatusUpdate{1, 5, 0, 0, kHomed});
    for (std::size_t cut = 0; cut < completed.size(); ++cut)
        EXPECT_EQ(decode(std::span(completed).first(cut)).status, DecodeStatus::NeedMore) << cut;
    // A header announcing an absurd data length (misaligned stream) is rejected one byte at a time.
    const Bytes garbage{0x64, 0x04, 0xFF, 0x7F, 0x81, 0x50};
    const auto d = decode(garbage);
    EXPECT_EQ(d.status, DecodeStatus::Invalid);
    EXPECT_EQ(d.consumed, 1u);
}

TEST(AptProtocol, HardwareInfoRoundTripsThe84BytePacket) {
    HardwareInfo info;
    info.serial = 55000123;
    info.model = "K10CR1";
    info.type = 16;
    info.firmware_major = 3;
    info.firmware_interim = 0;
    info.firmware_minor = 10;
    info.notes = "rotation mount";
    info.channels = 1;
    const Bytes bytes = hw_get_info(info);
    ASSERT_EQ(bytes.size(), 6u + 84u);
    EXPECT_EQ(bytes[0], 0x06);
    EXPECT_EQ(bytes[2], 84);
    EXPECT_EQ(bytes[4], 0x81);  // host | 0x80
    // Serial number is the first long of the packet: 55000123 = 0x03473C3B.
    EXPECT_EQ((Bytes{bytes[6], bytes[7], bytes[8], bytes[9]}), (Bytes{0x3B, 0x3C, 0x47, 0x03}));
    const auto parsed = parse_hw_info(decode(bytes).message);
    ASSERT_TRUE(parsed);
    EXPECT_EQ(parsed->serial, 55000123u);
    EXPECT_EQ(parsed->model, "K10CR1");
    EXPECT_EQ(parsed->firmware_major, 3);
    EXPECT_EQ(parsed->firmware_minor, 10);
    EXPECT_EQ(parsed->notes, "rotation mount");
    EXPECT_EQ(parsed->channels, 1);
}

TEST(AptProtocol, RichResponseCarriesCodeAndText) {
    const Bytes bytes = hw_rich_response({kMotMoveAbsolute, 16, "position error"});
    EXPECT_EQ(bytes.size(), 6u + 68u);
    const auto r = parse_rich_response(decode(bytes).message);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->message_id, kMotMoveAbsolute);
    EXPECT_EQ(r->code, 16);
    EXPECT_EQ(r->text, "position error");
    EXPECT_EQ(message_name(kMotMoveCompleted), "MGMSG_MOT_MOVE_COMPLETED");
}

}  // namespace
}  // namespace tirpol::acquisition::apt
