#pragma once
/// \file boson_fslp.h
/// FLIR Boson control link codec: FSLP framing and the command/reply payloads, pure functions over
/// bytes, no I/O. The Boson's USB CDC-ACM serial port (and its UART) carries these frames.
///
/// Sources (read, not copied):
/// - FLIR Boson SDK, UART connector (`UART_Connector_wrapper.cpp` / `FSLP.c`, `Client_Dispatcher`,
///   `Client_Packager`), `FunctionCodes.h`, `EnumTypes.h`, `ReturnCodes.h`; a public mirror is
///   github.com/eungiCho/BosonLinuxSDK (ClientFiles_C/). Framing bytes, escape pairs, CRC initial
///   value and the 12-byte command/reply headers are from the connector and dispatcher; function
///   codes, enums and return codes from the three headers.
/// - flirpy, github.com/LJMUAstroecology/flirpy, flirpy/camera/boson.py: the same frame layout
///   (">BBIII" header, CRC by `binascii.crc_hqx(..., 0x1D0F)` from the channel byte on, ">HB"
///   footer), BOSON_GETLASTFFCFRAMECOUNT (0x0005005D), which the 2015 SDK header lacks, and the
///   20-byte part number of BOSON_GETCAMERAPN (0x00050004).
///
/// Frame: 0x8E, channel, payload..., CRC hi, CRC lo, 0xAE. The CRC is CRC-16/CCITT (polynomial
/// 0x1021, not reflected, no final xor) started at 0x1D0F, i.e. CRC-16/AUG-CCITT, over the
/// unescaped channel byte and payload. Every byte between the start and end bytes (channel, payload
/// and both CRC bytes) that equals 0x8E, 0xAE or 0x9E is sent as 0x9E followed by 0x81, 0xA1 or
/// 0x91. Command payload (channel 0): sequence (u32), function code (u32), 0xFFFFFFFF, data. Reply
/// payload: sequence (u32), function code (u32), status (u32, FLR_RESULT; 0 = success), data. Every
/// multi-byte field is big-endian.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace tirpol::acquisition::boson {

inline constexpr std::uint8_t kStartByte = 0x8E;
inline constexpr std::uint8_t kEndByte = 0xAE;
inline constexpr std::uint8_t kEscapeByte = 0x9E;
inline constexpr std::uint8_t kEscapedStart = 0x81;
inline constexpr std::uint8_t kEscapedEnd = 0xA1;
inline constexpr std::uint8_t kEscapedEscape = 0x91;
inline constexpr std::uint8_t kCommandChannel = 0x00;
inline constexpr std::uint16_t kCrcInitial = 0x1D0F;
/// The third header word of a command (where a reply carries its status).
inline constexpr std::uint32_t kCommandStatusWord = 0xFFFFFFFF;
inline constexpr std::size_t kHeaderSize = 12;
/// The SDK's frame buffer (FRAME_BUF_SIZ): a longer frame is garbage, not a reply.
inline constexpr std::size_t kMaxFrameSize = 2048;

/// Function codes (SDK FunctionCodes.h unless noted). Data types in parentheses, big-endian.
enum FunctionCode : std::uint32_t {
    kGaoSetAveragerState = 0x0000000B,  ///< (u32 FLR_ENABLE_E: 0 off, 1 on)
    kGaoGetAveragerState = 0x0000000C,  ///< -> (u32)
    kRoicGetFrameCount = 0x00020002,    ///< -> (u32) frames since power-up
    kBosonGetCameraSn = 0x00050002,     ///< -> (u32)
    kBosonGetCameraPn = 0x00050004,     ///< -> (20 bytes ASCII, NUL-padded; flirpy get_part_number)
    kBosonRunFfc = 0x00050007,          ///< no data either way
    kBosonSetFfcTempThreshold =
        0x00050008,  ///< (u16, FPA change in 0.1 °C that triggers an auto FFC)
    kBosonGetFfcTempThreshold = 0x00050009,   ///< -> (u16)
    kBosonGetFfcInProgress = 0x0005000C,      ///< -> (i16, non-zero while an FFC runs)
    kBosonSetFfcMode = 0x00050012,            ///< (i32 FfcMode)
    kBosonGetFfcMode = 0x00050013,            ///< -> (i32 FfcMode)
    kBosonSetGainMode = 0x00050014,           ///< (i32 GainMode)
    kBosonGetGainMode = 0x00050015,           ///< -> (i32 GainMode)
    kBosonLookupFpaTempDegCx10 = 0x00050030,  ///< -> (i16, FPA temperature in 0.1 °C)
    kBosonGetFfcStatus = 0x00050054,          ///< -> (i32 FfcStatus)
    kBosonGetLastFfcFrameCount = 0x0005005D,  ///< -> (u32) frame count at the last FFC (flirpy)
    kDvoSetType = 0x0006000F,                 ///< (i32 DvoType) the CMOS/analog output's pixel type
    kDvoGetType = 0x00060010,                 ///< -> (i32 DvoType)
};

/// FLR_BOSON_FFCMODE_E.
enum class FfcMode : std::int32_t { Manual = 0, Auto = 1, External = 2, ShutterTest = 3 };
/// FLR_BOSON_FFCSTATUS_E.
enum class FfcStatus : std::int32_t {
    NoFfcPerformed = 0,
    Imminent = 1,
    InProgress = 2,
    Complete = 3
};
/// FLR_BOSON_GAINMODE_E.
enum class GainMode : std::int32_t { High = 0, Low = 1, Auto = 2, Dual = 3, Manual = 4 };
/// FLR_DVO_TYPE_E (2015 SDK): MONO16 is the 16-bit pre-AGC output.
enum class DvoType : std::int32_t { Mono16 = 0, Mono8 = 1, Color = 2, Analog = 3 };

/// FLR_RESULT values a camera returns in the reply's status word (SDK ReturnCodes.h).
enum ReturnCode : std::uint32_t {
    kSuccess = 0x000,
    kCamDispatchBadCommandId = 0x161,      ///< R_CAM_DSPCH_BAD_CMD_ID: unknown function code
    kCamPackageInsufficientBytes = 0x17D,  ///< R_CAM_PKG_INSUFFICIENT_BYTES: command data too short
    kCamApiInvalidInput = 0x181,           ///< R_CAM_API_INVALID_INPUT: a value out of range
};

const char* function_name(
    std::uint32_t function);  ///< "BOSON_RUNFFC", or "function 0x..." if unknown
std::string return_code_name(std::uint32_t code);  ///< "R_CAM_API_INVALID_INPUT (0x181)", ...

/// CRC-16/AUG-CCITT (poly 0x1021, init 0x1D0F, not reflected, no xor out); `crc` continues a
/// running value.
std::uint16_t crc16(std::span<const std::uint8_t> bytes, std::uint16_t crc = kCrcInitial);

/// Frames `payload` on `channel`: start byte, escaped channel + payload + CRC, end byte.
std::vector<std::uint8_t> encode_frame(std::uint8_t channel, std::span<const std::uint8_t> payload);

/// Big-endian field helpers.
void append_u32(std::vector<std::uint8_t>& out, std::uint32_t value);
void append_u16(std::vector<std::uint8_t>& out, std::uint16_t value);
std::uint32_t read_u32(std::span<const std::uint8_t> bytes, std::size_t offset);
std::uint16_t read_u16(std::span<const std::uint8_t> bytes, std::size_t offset);

struct Command {
    std::uint32_t sequence = 0;
    std::uint32_t function = 0;
    std::vector<std::uint8_t> data;
};
struct Reply {
    std::uint32_t sequence = 0;
    std::uint32_t function = 0;
    std::uint32_t status = kSuccess;
    std::vector<std::uint8_t> data;
};

/// A full frame on the command channel.
std::vector<std::uint8_t> encode_command(const Command& command);
std::vector<std::uint8_t> encode_reply(const Reply& reply);
/// A command payload (12-byte header with 0xFFFFFFFF in the third word); nullopt otherwise.
std::optional<Command> parse_command(std::span<const std::uint8_t> payload);
/// A reply payload (at least the 12-byte header); nullopt when shorter.
std::optional<Reply> parse_reply(std::span<const std::uint8_t> payload);

/// The sequence number after `sequence`, skipping any whose bytes hold 0x8E, 0x9E or 0xAE, as the
/// SDK packager does (fixSpecialBytes): such numbers would be escaped, which firmware tolerates but
/// some hosts' frame scanners do not.
std::uint32_t next_sequence(std::uint32_t sequence);

/// What the decoder found between a start byte and an end byte.
enum class FrameStatus {
    Ok,
    BadCrc,     ///< the CRC over channel + payload does not match the frame's
    BadEscape,  ///< 0x9E followed by something other than 0x81, 0xA1 or 0x91
    TooShort,   ///< fewer than 3 bytes (channel + CRC) between start and end
    TooLong,    ///< more than kMaxFrameSize bytes without an end byte
};
struct DecodedFrame {
    FrameStatus status = FrameStatus::Ok;
    std::uint8_t channel = 0;
    std::vector<std::uint8_t> payload;  ///< unescaped, without channel and CRC
    std::uint16_t received_crc = 0, computed_crc = 0;
};
/// "bad CRC: frame says 0x1234, computed 0xABCD over 17 bytes", ... for messages.
std::string describe(const DecodedFrame& frame);

/// Finds frames in a byte stream fed in arbitrary pieces. Bytes outside a frame are skipped
/// (counted); a start byte inside a frame abandons the partial frame (counted) and starts anew.
class FrameDecoder {
public:
    /// Consumes `bytes`; returns every frame that ended in them, good or bad, in order.
    std::vector<DecodedFrame> feed(std::span<const std::uint8_t> bytes);
    /// Bytes skipped outside frames or in abandoned partial frames so far.
    std::size_t discarded_bytes() const { return m_discarded; }

private:
    void abandon();
    bool m_in_frame = false, m_escape = false;
    std::vector<std::uint8_t> m_raw;  ///< unescaped bytes since the start byte
    std::size_t m_discarded = 0;
};

}  // namespace tirpol::acquisition::boson
