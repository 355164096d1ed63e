#pragma once
/// \file lepton_cci.h
/// The FLIR Lepton's command and control interface (CCI) as a PureThermal board tunnels it through
/// UVC extension-unit (XU) controls, and the Lepton's telemetry row. Sources: FLIR Lepton Software
/// Interface Description Document (IDD), doc 110-0144 (command ids, attribute layouts, the
/// telemetry row); the GroupGets PureThermal firmware and GetThermal (libuvc) for the tunnelling:
/// each CCI module is one extension unit (AGC 3, OEM 4, RAD 5, SYS 6, VID 7), the control selector
/// is the command id's offset within its module divided by 4, plus 1, a GET is a GET_CUR of the
/// attribute's bytes, a SET a SET_CUR of them, and a RUN a one-byte SET_CUR on the selector.
/// Attributes are 16-bit words, little-endian as the board's memory holds them; a 32-bit value
/// (an enum, a counter) is two words, the less significant first.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace tirpol::acquisition::lepton {

// Command ids (IDD 110-0144), without the GET/SET/RUN type bits.
inline constexpr std::uint16_t kSysCamUptime = 0x020C;             ///< 2 words: ms since power-up
inline constexpr std::uint16_t kSysFpaTemperatureKelvin = 0x0214;  ///< 1 word: K × 100
inline constexpr std::uint16_t kSysTelemetryEnable = 0x0218;       ///< 2 words: enum
inline constexpr std::uint16_t kSysTelemetryLocation = 0x021C;     ///< 2 words: 0 header, 1 footer
inline constexpr std::uint16_t kSysFfcShutterMode = 0x023C;        ///< 16 words: the object below
inline constexpr std::uint16_t kSysRunFfc = 0x0240;                ///< RUN
inline constexpr std::uint16_t kSysFfcStatus = 0x0244;             ///< 2 words: enum, 0 = ready
inline constexpr std::uint16_t kRadTLinearEnable = 0x0EC0;         ///< 2 words: enum
inline constexpr std::uint16_t kRadTLinearResolution = 0x0EC4;  ///< 2 words: 0 = 0.1 K, 1 = 0.01 K

/// PureThermal's extension unit for a command's CCI module; std::nullopt for a module it does not
/// map.
std::optional<std::uint8_t> xu_unit(std::uint16_t command_id);
/// The XU control selector of a command: ((id & 0xFF) >> 2) + 1.
std::uint8_t xu_selector(std::uint16_t command_id);

/// Attribute words ⇄ the bytes of a UVC GET_CUR/SET_CUR (little-endian words).
std::vector<std::uint8_t> words_to_bytes(std::span<const std::uint16_t> words);
std::vector<std::uint16_t> bytes_to_words(std::span<const std::uint8_t> bytes);
/// A 32-bit value as two words, less significant first, and back.
std::vector<std::uint16_t> u32_words(std::uint32_t value);
std::uint32_t u32_of(std::span<const std::uint16_t> words, std::size_t at);

/// LEP_SYS_FFC_SHUTTER_MODE_OBJ_T (16 words).
struct FfcShutterMode {
    enum Mode : std::uint32_t { Manual = 0, Auto = 1, External = 2 };
    std::uint32_t mode = Auto;
    std::uint32_t temp_lockout_state = 0;
    std::uint32_t video_freeze_during_ffc = 1;
    std::uint32_t ffc_desired = 0;
    std::uint32_t elapsed_since_last_ffc_ms = 0;
    std::uint32_t desired_ffc_period_ms = 180000;
    std::uint32_t explicit_command_to_open = 0;
    std::uint16_t desired_ffc_temp_delta_centi_k = 300;  ///< K × 100
    std::uint16_t imminent_delay_frames = 52;

    bool operator==(const FfcShutterMode&) const = default;
};
std::vector<std::uint16_t> encode_ffc_shutter_mode(const FfcShutterMode& mode);
/// std::nullopt unless exactly 16 words.
std::optional<FfcShutterMode> decode_ffc_shutter_mode(std::span<const std::uint16_t> words);

/// Telemetry row A (IDD 110-0144 / Lepton engineering datasheet, "Telemetry"): the fields the
/// capture uses.
struct Telemetry {
    std::uint32_t uptime_ms = 0;              ///< words 1–2
    std::uint32_t status_bits = 0;            ///< words 3–4
    std::uint32_t frame_counter = 0;          ///< words 20–21
    double fpa_temperature_k = 0.0;           ///< word 24, K × 100
    double fpa_temperature_at_ffc_k = 0.0;    ///< word 29, K × 100
    std::uint32_t uptime_at_last_ffc_ms = 0;  ///< words 30–31
    /// Status bits 4–5: 0 never commanded, 1 imminent, 2 in progress, 3 complete.
    int ffc_state() const { return static_cast<int>((status_bits >> 4) & 0x3u); }
};
inline constexpr std::size_t kTelemetryRowWords = 80;
/// Parses row A (at least 32 words); std::nullopt when shorter or its revision word is 0.
std::optional<Telemetry> parse_telemetry(std::span<const std::uint16_t> row);
/// Builds row A from the fields (the simulated Lepton in tests; a word layout check).
std::vector<std::uint16_t> encode_telemetry(const Telemetry& t);

}  // namespace tirpol::acquisition::lepton
