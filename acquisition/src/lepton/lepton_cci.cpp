#include "tirpol/acquisition/internal/lepton_cci.h"

#include <cmath>

namespace tirpol::acquisition::lepton {

std::optional<std::uint8_t> xu_unit(std::uint16_t command_id) {
    // The upper two bits (OEM, protection) do not choose the module.
    switch (command_id & 0x3F00) {
        case 0x0100:
            return 3;  // AGC
        case 0x0800:
            return 4;  // OEM
        case 0x0E00:
            return 5;  // RAD
        case 0x0200:
            return 6;  // SYS
        case 0x0300:
            return 7;  // VID
        default:
            return std::nullopt;
    }
}

std::uint8_t xu_selector(std::uint16_t command_id) {
    return static_cast<std::uint8_t>(((command_id & 0x00FF) >> 2) + 1);
}

std::vector<std::uint8_t> words_to_bytes(std::span<const std::uint16_t> words) {
    std::vector<std::uint8_t> out;
    out.reserve(words.size() * 2);
    for (std::uint16_t w : words) {
        out.push_back(static_cast<std::uint8_t>(w & 0xFF));
        out.push_back(static_cast<std::uint8_t>(w >> 8));
    }
    return out;
}

std::vector<std::uint16_t> bytes_to_words(std::span<const std::uint8_t> bytes) {
    std::vector<std::uint16_t> out(bytes.size() / 2);
    for (std::size_t i = 0; i < out.size(); ++i)
        out[i] = static_cast<std::uint16_t>(bytes[2 * i] | (bytes[2 * i + 1] << 8));
    return out;
}

std::vector<std::uint16_t> u32_words(std::uint32_t value) {
    return {static_cast<std::uint16_t>(value & 0xFFFF), static_cast<std::uint16_t>(value >> 16)};
}

std::uint32_t u32_of(std::span<const std::uint16_t> words, std::size_t at) {
    return static_cast<std::uint32_t>(words[at]) |
           (static_cast<std::uint32_t>(words[at + 1]) << 16);
}

std::vector<std::uint16_t> encode_ffc_shutter_mode(const FfcShutterMode& m) {
    std::vector<std::uint16_t> w;
    for (std::uint32_t v :
         {m.mode, m.temp_lockout_state, m.video_freeze_during_ffc, m.ffc_desired,
          m.elapsed_since_last_ffc_ms, m.desired_ffc_period_ms, m.explicit_command_to_open}) {
        const auto pair = u32_words(v);
        w.insert(w.end(), pair.begin(), pair.end());
    }
    w.push_back(m.desired_ffc_temp_delta_centi_k);
    w.push_back(m.imminent_delay_frames);
    return w;
}

std::optional<FfcShutterMode> decode_ffc_shutter_mode(std::span<const std::uint16_t> w) {
    if (w.size() != 16) return std::nullopt;
    FfcShutterMode m;
    m.mode = u32_of(w, 0);
    m.temp_lockout_state = u32_of(w, 2);
    m.video_freeze_during_ffc = u32_of(w, 4);
    m.ffc_desired = u32_of(w, 6);
    m.elapsed_since_last_ffc_ms = u32_of(w, 8);
    m.desired_ffc_period_ms = u32_of(w, 10);
    m.explicit_command_to_open = u32_of(w, 12);
    m.desired_ffc_temp_delta_centi_k = w[14];
    m.imminent_delay_frames = w[15];
    return m;
}

std::optional<Telemetry> parse_telemetry(std::span<const std::uint16_t> row) {
    if (row.size() < 32 || row[0] == 0) return std::nullopt;
    Telemetry t;
    t.uptime_ms = u32_of(row, 1);
    t.status_bits = u32_of(row, 3);
    t.frame_counter = u32_of(row, 20);
    t.fpa_temperature_k = row[24] / 100.0;
    t.fpa_temperature_at_ffc_k = row[29] / 100.0;
    t.uptime_at_last_ffc_ms = u32_of(row, 30);
    return t;
}

std::vector<std::uint16_t> encode_telemetry(const Telemetry& t) {
    std::vector<std::uint16_t> row(kTelemetryRowWords, 0);
    row[0] = 14;  // telemetry revision
    auto put32 = [&](std::size_t at, std::uint32_t v) {
        row[at] = static_cast<std::uint16_t>(v & 0xFFFF);
        row[at + 1] = static_cast<std::uint16_t>(v >> 16);
    };
    put32(1, t.uptime_ms);
    put32(3, t.status_bits);
    put32(20, t.frame_counter);
    row[24] = static_cast<std::uint16_t>(std::lround(t.fpa_temperature_k * 100.0));
    row[29] = static_cast<std::uint16_t>(std::lround(t.fpa_temperature_at_ffc_k * 100.0));
    put32(30, t.uptime_at_last_ffc_ms);
    return row;
}

}  // namespace tirpol::acquisition::lepton
