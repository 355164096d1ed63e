#include "tirpol/acquisition/internal/apt_protocol.h"

#include <fmt/format.h>

namespace tirpol::acquisition::apt {

namespace {
void put_u16(std::vector<std::uint8_t>& out, std::uint16_t v) {
    out.push_back(static_cast<std::uint8_t>(v & 0xFF));
    out.push_back(static_cast<std::uint8_t>(v >> 8));
}
void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>((v >> (8 * i)) & 0xFF));
}
std::uint16_t get_u16(std::span<const std::uint8_t> b, std::size_t at) {
    return static_cast<std::uint16_t>(b[at] | (b[at + 1] << 8));
}
std::uint32_t get_u32(std::span<const std::uint8_t> b, std::size_t at) {
    return static_cast<std::uint32_t>(b[at]) | (static_cast<std::uint32_t>(b[at + 1]) << 8) |
           (static_cast<std::uint32_t>(b[at + 2]) << 16) |
           (static_cast<std::uint32_t>(b[at + 3]) << 24);
}
/// Fixed-width text field: up to the first NUL, trailing spaces removed.
std::string get_text(std::span<const std::uint8_t> b, std::size_t at, std::size_t width) {
    std::string s;
    for (std::size_t i = 0; i < width && b[at + i] != 0; ++i)
        s.push_back(static_cast<char>(b[at + i]));
    while (!s.empty() && s.back() == ' ') s.pop_back();
    return s;
}
void put_text(std::vector<std::uint8_t>& out, const std::string& s, std::size_t width) {
    for (std::size_t i = 0; i < width; ++i)
        out.push_back(i < s.size() ? static_cast<std::uint8_t>(s[i]) : 0);
}
}  // namespace

std::vector<std::uint8_t> encode_short(std::uint16_t id, std::uint8_t param1, std::uint8_t param2,
                                       std::uint8_t dest, std::uint8_t source) {
    std::vector<std::uint8_t> out;
    put_u16(out, id);
    out.push_back(param1);
    out.push_back(param2);
    out.push_back(dest);
    out.push_back(source);
    return out;
}

std::vector<std::uint8_t> encode_long(std::uint16_t id, std::span<const std::uint8_t> data,
                                      std::uint8_t dest, std::uint8_t source) {
    std::vector<std::uint8_t> out;
    put_u16(out, id);
    put_u16(out, static_cast<std::uint16_t>(data.size()));
    out.push_back(static_cast<std::uint8_t>(dest | kDataPacketFlag));
    out.push_back(source);
    out.insert(out.end(), data.begin(), data.end());
    return out;
}

std::vector<std::uint8_t> hw_req_info() { return encode_short(kHwReqInfo, 0, 0); }
std::vector<std::uint8_t> hw_no_flash_programming() {
    return encode_short(kHwNoFlashProgramming, 0, 0);
}
std::vector<std::uint8_t> mod_identify(std::uint8_t channel) {
    return encode_short(kModIdentify, channel, 0);
}
std::vector<std::uint8_t> mod_set_chan_enable_state(std::uint8_t channel, bool enable) {
    // The document encodes enable as 0x01 and disable as 0x02.
    return encode_short(kModSetChanEnableState, channel, enable ? 0x01 : 0x02);
}
std::vector<std::uint8_t> mot_move_home(std::uint8_t channel) {
    return encode_short(kMotMoveHome, channel, 0);
}
std::vector<std::uint8_t> mot_req_ustatus_update(std::uint8_t channel) {
    return encode_short(kMotReqUStatusUpdate, channel, 0);
}
std::vector<std::uint8_t> mot_move_absolute(std::int32_t position, std::uint16_t channel) {
    std::vector<std::uint8_t> data;
    put_u16(data, channel);
    put_u32(data, static_cast<std::uint32_t>(position));
    return encode_long(kMotMoveAbsolute, data);
}

std::vector<std::uint8_t> mot_move_stop(std::uint8_t channel, StopMode mode) {
    return encode_short(kMotMoveStop, channel, static_cast<std::uint8_t>(mode));
}

Decoded decode_host_request(std::span<const std::uint8_t> bytes, std::uint8_t device_address) {
    if (bytes.size() >= kHeaderSize &&
        (bytes[5] != kHostAddress ||
         static_cast<std::uint8_t>(bytes[4] & ~kDataPacketFlag) != device_address)) {
        Decoded d;
        d.status = DecodeStatus::Invalid;
        d.consumed = 1;
        d.error = fmt::format("bytes {:02X} {:02X} … are not a header from the host to 0x{:02X}",
                              bytes[0], bytes[1], device_address);
        return d;
    }
    return decode(bytes);
}

Decoded decode(std::span<const std::uint8_t> bytes) {
    Decoded d;
    if (bytes.size() < kHeaderSize) return d;
    Message& m = d.message;
    m.id = get_u16(bytes, 0);
    m.source = bytes[5];
    const bool long_form = (bytes[4] & kDataPacketFlag) != 0;
    m.dest = static_cast<std::uint8_t>(bytes[4] & ~kDataPacketFlag);
    if (!long_form) {
        m.param1 = bytes[2];
        m.param2 = bytes[3];
        d.status = DecodeStatus::Complete;
        d.consumed = kHeaderSize;
        return d;
    }
    const std::size_t length = get_u16(bytes, 2);
    if (length == 0 || length > kMaxDataLength) {
        d.status = DecodeStatus::Invalid;
        d.consumed = 1;
        d.error =
            fmt::format("APT header for {} announces a data packet of {} bytes (expected 1..{})",
                        message_name(m.id), length, kMaxDataLength);
        return d;
    }
    if (bytes.size() < kHeaderSize + length) return d;
    m.data.assign(bytes.begin() + static_cast<std::ptrdiff_t>(kHeaderSize),
                  bytes.begin() + static_cast<std::ptrdiff_t>(kHeaderSize + length));
    d.status = DecodeStatus::Complete;
    d.consumed = kHeaderSize + length;
    return d;
}

std::optional<HardwareInfo> parse_hw_info(const Message& m) {
    if (m.id != kHwGetInfo || m.data.size() != 84) return std::nullopt;
    const std::span<const std::uint8_t> b(m.data);
    HardwareInfo info;
    info.serial = get_u32(b, 0);
    info.model = get_text(b, 4, 8);
    info.type = get_u16(b, 12);
    info.firmware_minor = b[14];
    info.firmware_interim = b[15];
    info.firmware_major = b[16];
    info.notes = get_text(b, 18, 48);
    info.hardware_version = get_u16(b, 78);
    info.mod_state = get_u16(b, 80);
    info.channels = get_u16(b, 82);
    return info;
}

std::vector<std::uint8_t> hw_get_info(const HardwareInfo& info, std::uint8_t source) {
    std::vector<std::uint8_t> data;
    put_u32(data, info.serial);
    put_text(data, info.model, 8);
    put_u16(data, info.type);
    data.push_back(static_cast<std::uint8_t>(info.firmware_minor));
    data.push_back(static_cast<std::uint8_t>(info.firmware_interim));
    data.push_back(static_cast<std::uint8_t>(info.firmware_major));
    data.push_back(0);
    put_text(data, info.notes, 48);
    put_text(data, "", 12);
    put_u16(data, info.hardware_version);
    put_u16(data, info.mod_state);
    put_u16(data, info.channels);
    return encode_long(kHwGetInfo, data, kHostAddress, source);
}

std::optional<StatusUpdate> parse_status_update(const Message& m) {
    if ((m.id != kMotMoveCompleted && m.id != kMotMoveStopped && m.id != kMotGetUStatusUpdate) ||
        m.data.size() != 14)
        return std::nullopt;
    const std::span<const std::uint8_t> b(m.data);
    StatusUpdate s;
    s.channel = get_u16(b, 0);
    s.position = static_cast<std::int32_t>(get_u32(b, 2));
    s.velocity = get_u16(b, 6);
    s.motor_current = static_cast<std::int16_t>(get_u16(b, 8));
    s.status_bits = get_u32(b, 10);
    return s;
}

std::vector<std::uint8_t> status_message(std::uint16_t id, const StatusUpdate& s,
                                         std::uint8_t source) {
    std::vector<std::uint8_t> data;
    put_u16(data, s.channel);
    put_u32(data, static_cast<std::uint32_t>(s.position));
    put_u16(data, s.velocity);
    put_u16(data, static_cast<std::uint16_t>(s.motor_current));
    put_u32(data, s.status_bits);
    return encode_long(id, data, kHostAddress, source);
}

std::optional<RichResponse> parse_rich_response(const Message& m) {
    if (m.id != kHwRichResponse || m.data.size() != 68) return std::nullopt;
    const std::span<const std::uint8_t> b(m.data);
    return RichResponse{get_u16(b, 0), get_u16(b, 2), get_text(b, 4, 64)};
}

std::vector<std::uint8_t> hw_rich_response(const RichResponse& r, std::uint8_t source) {
    std::vector<std::uint8_t> data;
    put_u16(data, r.message_id);
    put_u16(data, r.code);
    put_text(data, r.text, 64);
    return encode_long(kHwRichResponse, data, kHostAddress, source);
}

std::string message_name(std::uint16_t id) {
    switch (id) {
        case kHwReqInfo:
            return "MGMSG_HW_REQ_INFO";
        case kHwGetInfo:
            return "MGMSG_HW_GET_INFO";
        case kHwNoFlashProgramming:
            return "MGMSG_HW_NO_FLASH_PROGRAMMING";
        case kHwResponse:
            return "MGMSG_HW_RESPONSE";
        case kHwRichResponse:
            return "MGMSG_HW_RICHRESPONSE";
        case kModSetChanEnableState:
            return "MGMSG_MOD_SET_CHANENABLESTATE";
        case kModIdentify:
            return "MGMSG_MOD_IDENTIFY";
        case kMotMoveHome:
            return "MGMSG_MOT_MOVE_HOME";
        case kMotMoveHomed:
            return "MGMSG_MOT_MOVE_HOMED";
        case kMotMoveAbsolute:
            return "MGMSG_MOT_MOVE_ABSOLUTE";
        case kMotMoveCompleted:
            return "MGMSG_MOT_MOVE_COMPLETED";
        case kMotMoveStop:
            return "MGMSG_MOT_MOVE_STOP";
        case kMotMoveStopped:
            return "MGMSG_MOT_MOVE_STOPPED";
        case kMotReqUStatusUpdate:
            return "MGMSG_MOT_REQ_USTATUSUPDATE";
        case kMotGetUStatusUpdate:
            return "MGMSG_MOT_GET_USTATUSUPDATE";
        default:
            return fmt::format("0x{:04X}", id);
    }
}

}  // namespace tirpol::acquisition::apt
