// FLIR Boson FSLP codec. Sources: the Boson SDK's UART connector and dispatcher (frame bytes,
// escape pairs, CRC start 0x1D0F over the unescaped channel + payload, CRC bytes escaped too,
// 12-byte headers) and flirpy's boson.py (the same layout, CRC by binascii.crc_hqx(frame[1:-3],
// 0x1D0F)).

#include "tirpol/acquisition/internal/boson_fslp.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace tirpol::acquisition::boson {
namespace {

// Bit-at-a-time CRC-16, MSB first, polynomial 0x1021: the textbook definition, independent of the
// codec's table.
std::uint16_t reference_crc(std::span<const std::uint8_t> bytes, std::uint16_t crc) {
    for (std::uint8_t b : bytes) {
        crc = static_cast<std::uint16_t>(crc ^ (b << 8));
        for (int i = 0; i < 8; ++i)
            crc = static_cast<std::uint16_t>((crc & 0x8000) ? (crc << 1) ^ 0x1021 : crc << 1);
    }
    return crc;
}

bool is_special(std::uint8_t b) { return b == 0x8E || b == 0xAE || b == 0x9E; }

TEST(BosonFslp, CrcIsAugCcittWithItsCatalogueCheckValue) {
    // CRC-16/AUG-CCITT (width 16, poly 0x1021, init 0x1D0F, refin/refout false, xorout 0): its
    // check value over ASCII "123456789" is 0xE5CC (Greg Cook's CRC catalogue, reveng). Python's
    // binascii.crc_hqx(b"123456789", 0x1D0F), the call flirpy uses, gives the same 0xE5CC.
    const std::string check = "123456789";
    const std::span<const std::uint8_t> bytes(reinterpret_cast<const std::uint8_t*>(check.data()),
                                              check.size());
    EXPECT_EQ(crc16(bytes), 0xE5CC);
    EXPECT_EQ(reference_crc(bytes, 0x1D0F), 0xE5CC);
    // Init 0xFFFF (CRC-16/CCITT-FALSE) would give 0x29B1: the initial value matters.
    EXPECT_EQ(crc16(bytes, 0xFFFF), 0x29B1);
    std::vector<std::uint8_t> all(256);
    for (int i = 0; i < 256; ++i) all[i] = static_cast<std::uint8_t>(i * 37 + 11);
    EXPECT_EQ(crc16(all), reference_crc(all, 0x1D0F));
}

TEST(BosonFslp, CommandLayoutIsBigEndianSequenceFunctionAndAllOnes) {
    const auto frame = encode_command({0x01020304, kBosonSetFfcMode, {0x00, 0x00, 0x00, 0x00}});
    const std::vector<std::uint8_t> body = {0x00,                     // channel
                                            0x01, 0x02, 0x03, 0x04,   // sequence
                                            0x00, 0x05, 0x00, 0x12,   // BOSON_SETFFCMODE
                                            0xFF, 0xFF, 0xFF, 0xFF,   // command marker
                                            0x00, 0x00, 0x00, 0x00};  // FLR_BOSON_MANUAL_FFC
    const std::uint16_t crc = reference_crc(body, 0x1D0F);
    ASSERT_FALSE(is_special(static_cast<std::uint8_t>(crc >> 8)) ||
                 is_special(static_cast<std::uint8_t>(crc & 0xFF)))
        << "pick another sequence for this test";
    std::vector<std::uint8_t> expected = {0x8E};
    expected.insert(expected.end(), body.begin(), body.end());
    expected.insert(expected.end(), {static_cast<std::uint8_t>(crc >> 8),
                                     static_cast<std::uint8_t>(crc & 0xFF), 0xAE});
    EXPECT_EQ(frame, expected);
}

TEST(BosonFslp, EverySpecialByteIsEscapedAndComesBack) {
    const std::vector<std::uint8_t> payload = {0x8E, 0x01, 0xAE, 0x9E, 0x9E,
                                               0x81, 0x91, 0xA1, 0x8E};
    const auto frame = encode_frame(kCommandChannel, payload);
    // Between the start and end bytes nothing but escape pairs may hold a special byte.
    ASSERT_GE(frame.size(), 2u);
    for (std::size_t i = 1; i + 1 < frame.size(); ++i) {
        if (frame[i] == 0x9E) {
            ASSERT_TRUE(frame[i + 1] == 0x81 || frame[i + 1] == 0xA1 || frame[i + 1] == 0x91) << i;
            ++i;
        } else {
            EXPECT_FALSE(is_special(frame[i])) << "bare special byte at " << i;
        }
    }
    const std::vector<std::uint8_t> start_pair = {0x9E, 0x81}, end_pair = {0x9E, 0xA1},
                                    escape_pair = {0x9E, 0x91};
    EXPECT_NE(std::search(frame.begin(), frame.end(), start_pair.begin(), start_pair.end()),
              frame.end());
    EXPECT_NE(std::search(frame.begin(), frame.end(), end_pair.begin(), end_pair.end()),
              frame.end());
    EXPECT_NE(std::search(frame.begin(), frame.end(), escape_pair.begin(), escape_pair.end()),
              frame.end());
    FrameDecoder decoder;
    const auto frames = decoder.feed(frame);
    ASSERT_EQ(frames.size(), 1u);
    EXPECT_EQ(frames[0].status, FrameStatus::Ok) << describe(frames[0]);
    EXPECT_EQ(frames[0].payload, payload);
}

TEST(BosonFslp, CrcBytesThatAreSpecialAreEscapedToo) {
    // Search sequence numbers for each case: the CRC's high byte, then its low byte, special.
    for (int which = 0; which < 2; ++which) {
        bool found = false;
        for (std::uint32_t seq = 0; seq < 100000 && !found; ++seq) {
            std::vector<std::uint8_t> body = {0x00};
            append_u32(body, seq);
            append_u32(body, kBosonRunFfc);
            append_u32(body, kCommandStatusWord);
            const std::uint16_t crc = reference_crc(body, 0x1D0F);
            const auto byte = static_cast<std::uint8_t>(which == 0 ? crc >> 8 : crc & 0xFF);
            if (!is_special(byte)) continue;
            found = true;
            const auto frame = encode_command({seq, kBosonRunFfc, {}});
            EXPECT_EQ(frame.size(), 1 + body.size() + 3 + 1)
                << "one escape pair for the CRC byte (seq " << seq << ")";
            FrameDecoder decoder;
            const auto frames = decoder.feed(frame);
            ASSERT_EQ(frames.size(), 1u);
            EXPECT_EQ(frames[0].status, FrameStatus::Ok) << describe(frames[0]);
            EXPECT_EQ(frames[0].received_crc, crc);
        }
        EXPECT_TRUE(found) << "no sequence number gives a special CRC byte " << which;
    }
}

TEST(BosonFslp, CommandAndReplyRoundTrip) {
    const Command command{77, kBosonLookupFpaTempDegCx10, {0xAE, 0x8E}};
    FrameDecoder decoder;
    auto frames = decoder.feed(encode_command(command));
    ASSERT_EQ(frames.size(), 1u);
    const auto parsed = parse_command(frames[0].payload);
    ASSERT_TRUE(parsed);
    EXPECT_EQ(parsed->sequence, 77u);
    EXPECT_EQ(parsed->function, kBosonLookupFpaTempDegCx10);
    EXPECT_EQ(parsed->data, command.data);
    // A reply is not a command: its third word is a status, not 0xFFFFFFFF.
    frames = decoder.feed(
        encode_reply({77, kBosonLookupFpaTempDegCx10, kCamApiInvalidInput, {0x01, 0x5E}}));
    ASSERT_EQ(frames.size(), 1u);
    EXPECT_FALSE(parse_command(frames[0].payload));
    const auto reply = parse_reply(frames[0].payload);
    ASSERT_TRUE(reply);
    EXPECT_EQ(reply->status, kCamApiInvalidInput);
    EXPECT_EQ(reply->data, (std::vector<std::uint8_t>{0x01, 0x5E}));
    EXPECT_FALSE(parse_reply(std::vector<std::uint8_t>(11, 0)));
    EXPECT_EQ(return_code_name(kCamApiInvalidInput), "R_CAM_API_INVALID_INPUT (0x181)");
}

TEST(BosonFslp, DecoderFindsFramesSplitAtEveryByteWithGarbageBetween) {
    const std::vector<std::uint8_t> f1 = encode_reply({1, kBosonRunFfc, kSuccess, {}});
    const std::vector<std::uint8_t> f2 =
        encode_reply({2, kBosonGetFfcStatus, kSuccess, {0, 0, 0, 3}});
    const std::vector<std::uint8_t> f3 =
        encode_reply({3, kBosonLookupFpaTempDegCx10, kSuccess, {0x8E, 0x9E}});
    const std::vector<std::uint8_t> garbage1 = {0x00, 0x55, 0xAE, 0x9E,
                                                0x12};  // noise: an end and an escape
    const std::vector<std::uint8_t> garbage2 = {0xFF, 0xAE};
    std::vector<std::uint8_t> stream = garbage1;
    for (const auto* part : {&f1, &garbage2, &f2, &f3, &garbage1})
        stream.insert(stream.end(), part->begin(), part->end());
    auto check = [&](const std::vector<DecodedFrame>& frames, const std::string& where) {
        ASSERT_EQ(frames.size(), 3u) << where;
        for (std::size_t i = 0; i < 3; ++i) {
            EXPECT_EQ(frames[i].status, FrameStatus::Ok) << where << ": " << describe(frames[i]);
            const auto reply = parse_reply(frames[i].payload);
            ASSERT_TRUE(reply) << where;
            EXPECT_EQ(reply->sequence, i + 1) << where;
        }
    };
    for (std::size_t split = 0; split <= stream.size(); ++split) {
        FrameDecoder decoder;
        auto frames = decoder.feed(std::span(stream).first(split));
        const auto rest = decoder.feed(std::span(stream).subspan(split));
        frames.insert(frames.end(), rest.begin(), rest.end());
        check(frames, "split at " + std::to_string(split));
        EXPECT_EQ(decoder.discarded_bytes(), 2 * garbage1.size() + garbage2.size());
    }
    FrameDecoder decoder;
    std::vector<DecodedFrame> frames;
    for (std::uint8_t b : stream) {
        const auto found = decoder.feed(std::span(&b, 1));
        frames.insert(frames.end(), found.begin(), found.end());
    }
    check(frames, "byte by byte");
}

TEST(BosonFslp, BadFramesAreReportedAndTheNextGoodOneIsStillFound) {
    auto corrupt = encode_reply({9, kBosonGetFfcMode, kSuccess, {0, 0, 0, 1}});
    corrupt[8] ^= 0x01;  // a bit error in the function code
    const auto good = encode_reply({10, kBosonGetFfcMode, kSuccess, {0, 0, 0, 0}});
    const auto truncated =
        std::vector<std::uint8_t>(good.begin(), good.begin() + 7);  // no end byte
    const std::vector<std::uint8_t> bad_escape = {0x8E, 0x00, 0x9E, 0x42, 0x00, 0x00, 0xAE};
    const std::vector<std::uint8_t> too_short = {0x8E, 0x00, 0x12, 0xAE};
    std::vector<std::uint8_t> stream;
    for (const std::vector<std::uint8_t>* part :
         std::initializer_list<const std::vector<std::uint8_t>*>{&corrupt, &bad_escape, &too_short,
                                                                 &truncated, &good})
        stream.insert(stream.end(), part->begin(), part->end());
    FrameDecoder decoder;
    const auto frames = decoder.feed(stream);
    ASSERT_EQ(frames.size(), 4u);
    EXPECT_EQ(frames[0].status, FrameStatus::BadCrc);
    EXPECT_NE(frames[0].received_crc, frames[0].computed_crc);
    EXPECT_NE(describe(frames[0]).find("bad CRC"), std::string::npos) << describe(frames[0]);
    EXPECT_EQ(frames[1].status, FrameStatus::BadEscape);
    EXPECT_EQ(frames[2].status, FrameStatus::TooShort);
    EXPECT_EQ(frames[3].status, FrameStatus::Ok)
        << "the start byte of the good frame restarts after the truncated one";
    EXPECT_EQ(parse_reply(frames[3].payload)->sequence, 10u);
    // A start byte with no end within the SDK's frame buffer is dropped, not buffered forever.
    std::vector<std::uint8_t> endless(kMaxFrameSize + 10, 0x11);
    endless[0] = 0x8E;
    const auto long_frames = decoder.feed(endless);
    ASSERT_EQ(long_frames.size(), 1u);
    EXPECT_EQ(long_frames[0].status, FrameStatus::TooLong);
}

TEST(BosonFslp, SequenceNumbersSkipSpecialBytesAsTheSdkDoes) {
    EXPECT_EQ(next_sequence(0), 1u);
    EXPECT_EQ(next_sequence(0x8D), 0x8Fu);
    EXPECT_EQ(next_sequence(0x9D), 0x9Fu);
    EXPECT_EQ(next_sequence(0xAD), 0xAFu);
    EXPECT_EQ(next_sequence(0x8DFF), 0x8F00u);
    EXPECT_EQ(next_sequence(0xFFFFFFFF), 0u);
}

}  // namespace
}  // namespace tirpol::acquisition::boson
