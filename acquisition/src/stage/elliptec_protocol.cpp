#include "tirpol/acquisition/internal/elliptec_protocol.h"

#include <fmt/format.h>

namespace tirpol::acquisition::elliptec {

namespace {
std::optional<std::uint32_t> parse_hex(std::string_view text) {
    if (text.empty() || text.size() > 8) return std::nullopt;
    std::uint32_t v = 0;
    for (char c : text) {
        int digit;
        if (c >= '0' && c <= '9')
            digit = c - '0';
        else if (c >= 'A' && c <= 'F')
            digit = c - 'A' + 10;
        else if (c >= 'a' && c <= 'f')
            digit = c - 'a' + 10;
        else
            return std::nullopt;
        v = (v << 4) | static_cast<std::uint32_t>(digit);
    }
    return v;
}
std::string command(char address, std::string_view cmd, std::string_view data = {}) {
    std::string s(1, address);
    s.append(cmd);
    s.append(data);
    return s;
}
}  // namespace

bool valid_address(char c) { return (c >= '0' && c <= '9') || (c >= 'A' && c <= 'F'); }

std::string info_request(char address) { return command(address, "in"); }
std::string home(char address, bool clockwise) {
    return command(address, "ho", clockwise ? "0" : "1");
}
std::string move_absolute(char address, std::int32_t pulses) {
    return command(address, "ma", encode_position(pulses));
}
std::string get_position(char address) { return command(address, "gp"); }
std::string get_status(char address) { return command(address, "gs"); }
std::string stop(char address) { return command(address, "st"); }

std::string encode_position(std::int32_t pulses) {
    return fmt::format("{:08X}", static_cast<std::uint32_t>(pulses));
}

std::optional<std::int32_t> decode_position(std::string_view hex8) {
    if (hex8.size() != 8) return std::nullopt;
    const auto v = parse_hex(hex8);
    if (!v) return std::nullopt;
    return static_cast<std::int32_t>(*v);
}

std::optional<Reply> parse_reply(std::string_view line) {
    if (line.size() < 3 || !valid_address(line[0])) return std::nullopt;
    for (std::size_t i = 1; i < 3; ++i)
        if (line[i] < 'A' || line[i] > 'Z') return std::nullopt;
    return Reply{line[0], std::string(line.substr(1, 2)), std::string(line.substr(3))};
}

std::optional<DeviceInfo> parse_info(const Reply& reply) {
    // 2 + 8 + 4 + 2 + 1 + 1 + 4 + 8 = 30 characters after "IN".
    const std::string& d = reply.data;
    if (reply.code != "IN" || d.size() != 30) return std::nullopt;
    DeviceInfo info;
    const auto type = parse_hex(std::string_view(d).substr(0, 2));
    const auto firmware = parse_hex(std::string_view(d).substr(14, 2));
    const auto hardware = parse_hex(std::string_view(d).substr(17, 1));
    const auto travel = parse_hex(std::string_view(d).substr(18, 4));
    const auto pulses = parse_hex(std::string_view(d).substr(22, 8));
    if (!type || !firmware || !hardware || !travel || !pulses || (d[16] != '0' && d[16] != '1'))
        return std::nullopt;
    info.motor_type = static_cast<int>(*type);
    info.serial = d.substr(2, 8);
    info.year = d.substr(10, 4);
    info.firmware = static_cast<int>(*firmware);
    info.imperial_thread = d[16] == '1';
    info.hardware_release = static_cast<int>(*hardware);
    info.travel = *travel;
    info.pulses = *pulses;
    return info;
}

std::string encode_info(const DeviceInfo& i) {
    return fmt::format("{:02X}{:>8.8}{:>4.4}{:02X}{}{:X}{:04X}{:08X}", i.motor_type, i.serial,
                       i.year, i.firmware, i.imperial_thread ? '1' : '0', i.hardware_release & 0xF,
                       i.travel, i.pulses);
}

std::string status_meaning(int code) {
    switch (code) {
        case kOk:
            return "OK, no error";
        case kCommunicationTimeout:
            return "Communication time out";
        case kMechanicalTimeout:
            return "Mechanical time out";
        case kCommandError:
            return "Command error or not supported";
        case kValueOutOfRange:
            return "Value out of range";
        case kModuleIsolated:
            return "Module isolated";
        case kModuleOutOfIsolation:
            return "Module out of isolation";
        case kInitializingError:
            return "Initializing error";
        case kThermalError:
            return "Thermal error";
        case kBusy:
            return "Busy";
        case kSensorError:
            return "Sensor error (may appear during self test)";
        case kMotorError:
            return "Motor error (may appear during self test)";
        case kOutOfRange:
            return "Out of range (e.g. stage asked to move beyond its travel)";
        case kOverCurrentError:
            return "Over current error";
        default:
            return fmt::format("Reserved status code {}", code);
    }
}

std::optional<int> parse_status(const Reply& reply) {
    if (reply.code != "GS" || reply.data.size() != 2) return std::nullopt;
    const auto v = parse_hex(reply.data);
    if (!v) return std::nullopt;
    return static_cast<int>(*v);
}

std::optional<std::string> take_line(std::string& buffer) {
    const auto end = buffer.find("\r\n");
    if (end == std::string::npos) return std::nullopt;
    std::string line = buffer.substr(0, end);
    buffer.erase(0, end + 2);
    return line;
}

}  // namespace tirpol::acquisition::elliptec
