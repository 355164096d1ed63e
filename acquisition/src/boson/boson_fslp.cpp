#include "tirpol/acquisition/internal/boson_fslp.h"

#include <fmt/format.h>

#include <array>

namespace tirpol::acquisition::boson {

namespace {
// The MSB-first table of polynomial 0x1021, built once at compile time.
constexpr std::array<std::uint16_t, 256> make_crc_table() {
    std::array<std::uint16_t, 256> table{};
    for (unsigned i = 0; i < 256; ++i) {
        auto v = static_cast<std::uint16_t>(i << 8);
        for (int bit = 0; bit < 8; ++bit)
            v = static_cast<std::uint16_t>((v & 0x8000) ? (v << 1) ^ 0x1021 : v << 1);
        table[i] = v;
    }
    return table;
}
constexpr auto kCrcTable = make_crc_table();

bool special(std::uint8_t b) { return b == kStartByte || b == kEndByte || b == kEscapeByte; }

void append_escaped(std::vector<std::uint8_t>& out, std::uint8_t b) {
    if (!special(b)) {
        out.push_back(b);
        return;
    }
    out.push_back(kEscapeByte);
    out.push_back(b == kStartByte ? kEscapedStart : b == kEndByte ? kEscapedEnd : kEscapedEscape);
}

std::optional<std::uint8_t> unescape(std::uint8_t b) {
    switch (b) {
        case kEscapedStart:
            return kStartByte;
        case kEscapedEnd:
            return kEndByte;
        case kEscapedEscape:
            return kEscapeByte;
        default:
            return std::nullopt;
    }
}

std::vector<std::uint8_t> header_payload(std::uint32_t sequence, std::uint32_t function,
                                         std::uint32_t third,
                                         const std::vector<std::uint8_t>& data) {
    std::vector<std::uint8_t> payload;
    payload.reserve(kHeaderSize + data.size());
    append_u32(payload, sequence);
    append_u32(payload, function);
    append_u32(payload, third);
    payload.insert(payload.end(), data.begin(), data.end());
    return payload;
}
}  // namespace

const char* function_name(std::uint32_t function) {
    switch (function) {
        case kGaoSetAveragerState:
            return "GAO_SETAVERAGERSTATE";
        case kGaoGetAveragerState:
            return "GAO_GETAVERAGERSTATE";
        case kRoicGetFrameCount:
            return "ROIC_GETFRAMECOUNT";
        case kBosonGetCameraSn:
            return "BOSON_GETCAMERASN";
        case kBosonGetCameraPn:
            return "BOSON_GETCAMERAPN";
        case kBosonRunFfc:
            return "BOSON_RUNFFC";
        case kBosonSetFfcTempThreshold:
            return "BOSON_SETFFCTEMPTHRESHOLD";
        case kBosonGetFfcTempThreshold:
            return "BOSON_GETFFCTEMPTHRESHOLD";
        case kBosonGetFfcInProgress:
            return "BOSON_GETFFCINPROGRESS";
        case kBosonSetFfcMode:
            return "BOSON_SETFFCMODE";
        case kBosonGetFfcMode:
            return "BOSON_GETFFCMODE";
        case kBosonSetGainMode:
            return "BOSON_SETGAINMODE";
        case kBosonGetGainMode:
            return "BOSON_GETGAINMODE";
        case kBosonLookupFpaTempDegCx10:
            return "BOSON_LOOKUPFPATEMPDEGCX10";
        case kBosonGetFfcStatus:
            return "BOSON_GETFFCSTATUS";
        case kBosonGetLastFfcFrameCount:
            return "BOSON_GETLASTFFCFRAMECOUNT";
        case kDvoSetType:
            return "DVO_SETTYPE";
        case kDvoGetType:
            return "DVO_GETTYPE";
        default:
            return "an unknown function";
    }
}

std::string return_code_name(std::uint32_t code) {
    const char* name = code == kSuccess                       ? "R_SUCCESS"
                       : code == kCamDispatchBadCommandId     ? "R_CAM_DSPCH_BAD_CMD_ID"
                       : code == kCamPackageInsufficientBytes ? "R_CAM_PKG_INSUFFICIENT_BYTES"
                       : code == kCamApiInvalidInput          ? "R_CAM_API_INVALID_INPUT"
                                                              : "FLR_RESULT";
    return fmt::format("{} (0x{:X})", name, code);
}

std::uint16_t crc16(std::span<const std::uint8_t> bytes, std::uint16_t crc) {
    for (std::uint8_t b : bytes)
        crc = static_cast<std::uint16_t>((crc << 8) ^ kCrcTable[((crc >> 8) ^ b) & 0xFF]);
    return crc;
}

std::vector<std::uint8_t> encode_frame(std::uint8_t channel,
                                       std::span<const std::uint8_t> payload) {
    std::uint16_t crc = crc16(std::span<const std::uint8_t>(&channel, 1));
    crc = crc16(payload, crc);
    std::vector<std::uint8_t> out;
    out.reserve(payload.size() + 8);
    out.push_back(kStartByte);
    append_escaped(out, channel);
    for (std::uint8_t b : payload) append_escaped(out, b);
    append_escaped(out, static_cast<std::uint8_t>(crc >> 8));
    append_escaped(out, static_cast<std::uint8_t>(crc & 0xFF));
    out.push_back(kEndByte);
    return out;
}

void append_u32(std::vector<std::uint8_t>& out, std::uint32_t value) {
    for (int shift = 24; shift >= 0; shift -= 8)
        out.push_back(static_cast<std::uint8_t>(value >> shift));
}

void append_u16(std::vector<std::uint8_t>& out, std::uint16_t value) {
    out.push_back(static_cast<std::uint8_t>(value >> 8));
    out.push_back(static_cast<std::uint8_t>(value & 0xFF));
}

std::uint32_t read_u32(std::span<const std::uint8_t> bytes, std::size_t offset) {
    return (std::uint32_t{bytes[offset]} << 24) | (std::uint32_t{bytes[offset + 1]} << 16) |
           (std::uint32_t{bytes[offset + 2]} << 8) | std::uint32_t{bytes[offset + 3]};
}

std::uint16_t read_u16(std::span<const std::uint8_t> bytes, std::size_t offset) {
    return static_cast<std::uint16_t>((bytes[offset] << 8) | bytes[offset + 1]);
}

std::vector<std::uint8_t> encode_command(const Command& command) {
    return encode_frame(kCommandChannel, header_payload(command.sequence, command.function,
                                                        kCommandStatusWord, command.data));
}

std::vector<std::uint8_t> encode_reply(const Reply& reply) {
    return encode_frame(kCommandChannel,
                        header_payload(reply.sequence, reply.function, reply.status, reply.data));
}

std::optional<Command> parse_command(std::span<const std::uint8_t> payload) {
    if (payload.size() < kHeaderSize || read_u32(payload, 8) != kCommandStatusWord)
        return std::nullopt;
    return Command{
        read_u32(payload, 0), read_u32(payload, 4), {payload.begin() + kHeaderSize, payload.end()}};
}

std::optional<Reply> parse_reply(std::span<const std::uint8_t> payload) {
    if (payload.size() < kHeaderSize) return std::nullopt;
    return Reply{read_u32(payload, 0),
                 read_u32(payload, 4),
                 read_u32(payload, 8),
                 {payload.begin() + kHeaderSize, payload.end()}};
}

std::uint32_t next_sequence(std::uint32_t sequence) {
    for (;;) {
        ++sequence;
        bool clean = true;
        for (int shift = 0; shift < 32; shift += 8)
            clean = clean && !special(static_cast<std::uint8_t>(sequence >> shift));
        if (clean) return sequence;
    }
}

std::string describe(const DecodedFrame& frame) {
    switch (frame.status) {
        case FrameStatus::Ok:
            return fmt::format("frame on channel {} with {} payload bytes", frame.channel,
                               frame.payload.size());
        case FrameStatus::BadCrc:
            return fmt::format("bad CRC: the frame says 0x{:04X}, its {} bytes give 0x{:04X}",
                               frame.received_crc, frame.payload.size() + 1, frame.computed_crc);
        case FrameStatus::BadEscape:
            return "bad escape: 0x9E followed by a byte other than 0x81, 0xA1 or 0x91";
        case FrameStatus::TooShort:
            return "frame too short: fewer than 3 bytes (channel and CRC) between 0x8E and 0xAE";
        case FrameStatus::TooLong:
            return fmt::format("frame too long: no 0xAE within {} bytes of 0x8E", kMaxFrameSize);
    }
    return "unknown frame status";
}

void FrameDecoder::abandon() {
    m_discarded += m_raw.size() + 1;  // and the start byte
    m_raw.clear();
    m_in_frame = m_escape = false;
}

std::vector<DecodedFrame> FrameDecoder::feed(std::span<const std::uint8_t> bytes) {
    std::vector<DecodedFrame> frames;
    auto fail = [&](FrameStatus status) {
        DecodedFrame f;
        f.status = status;
        frames.push_back(std::move(f));
        abandon();
    };
    for (std::uint8_t b : bytes) {
        if (b == kStartByte) {
            if (m_in_frame) abandon();
            m_in_frame = true;
            m_escape = false;
            m_raw.clear();
            continue;
        }
        if (!m_in_frame) {
            ++m_discarded;
            continue;
        }
        if (m_escape) {
            m_escape = false;
            const auto original = unescape(b);
            if (!original) {
                fail(FrameStatus::BadEscape);
                continue;
            }
            m_raw.push_back(*original);
        } else if (b == kEscapeByte) {
            m_escape = true;
            continue;
        } else if (b == kEndByte) {
            if (m_raw.size() < 3) {
                fail(FrameStatus::TooShort);
                continue;
            }
            DecodedFrame f;
            const std::size_t body = m_raw.size() - 2;
            f.channel = m_raw[0];
            f.received_crc = read_u16(m_raw, body);
            f.computed_crc = crc16(std::span<const std::uint8_t>(m_raw.data(), body));
            f.status = f.received_crc == f.computed_crc ? FrameStatus::Ok : FrameStatus::BadCrc;
            f.payload.assign(m_raw.begin() + 1, m_raw.begin() + static_cast<std::ptrdiff_t>(body));
            frames.push_back(std::move(f));
            m_raw.clear();
            m_in_frame = false;
            continue;
        } else {
            m_raw.push_back(b);
        }
        if (m_raw.size() > kMaxFrameSize) fail(FrameStatus::TooLong);
    }
    return frames;
}

}  // namespace tirpol::acquisition::boson
