#pragma once
/// \file apt_protocol.h
/// Thorlabs APT binary protocol codec: pure functions over bytes, no I/O.
/// Source: Thorlabs, "Thorlabs APT Controllers Host-Controller Communications Protocol", Issue 2x
/// (https://www.thorlabs.com/Software/Motion%20Control/APT_Communications_Protocol.pdf), §2
/// "Message structure" and the message descriptions cited at each id below.
///
/// Every message starts with a 6-byte header, little endian:
///   no data packet:  [id lo][id hi][param1][param2][dest][source]
///   data packet:     [id lo][id hi][len lo][len hi][dest | 0x80][source] + len bytes
/// Host address 0x01, a single-channel USB controller (K10CR1, KST101, ...) is 0x50 ("generic USB
/// unit").

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace tirpol::acquisition::apt {

inline constexpr std::uint8_t kHostAddress = 0x01;
inline constexpr std::uint8_t kUsbDeviceAddress = 0x50;
inline constexpr std::uint8_t kDataPacketFlag = 0x80;
inline constexpr std::size_t kHeaderSize = 6;

/// Message ids used by tirpol (protocol document section in parentheses).
enum MessageId : std::uint16_t {
    kHwReqInfo = 0x0005,              ///< MGMSG_HW_REQ_INFO (Generic system control messages)
    kHwGetInfo = 0x0006,              ///< MGMSG_HW_GET_INFO, 84-byte data packet
    kHwNoFlashProgramming = 0x0018,   ///< MGMSG_HW_NO_FLASH_PROGRAMMING, sent once at start-up
    kHwResponse = 0x0080,             ///< MGMSG_HW_RESPONSE (unsolicited: an error occurred)
    kHwRichResponse = 0x0081,         ///< MGMSG_HW_RICHRESPONSE, 68-byte packet with code and text
    kModSetChanEnableState = 0x0210,  ///< MGMSG_MOD_SET_CHANENABLESTATE
    kModIdentify = 0x0223,            ///< MGMSG_MOD_IDENTIFY (flashes the front-panel LED)
    kMotMoveHome = 0x0443,            ///< MGMSG_MOT_MOVE_HOME
    kMotMoveHomed = 0x0444,           ///< MGMSG_MOT_MOVE_HOMED
    kMotMoveAbsolute = 0x0453,        ///< MGMSG_MOT_MOVE_ABSOLUTE (6-byte data packet form)
    kMotMoveCompleted = 0x0464,       ///< MGMSG_MOT_MOVE_COMPLETED, 14-byte status packet
    kMotMoveStop = 0x0465,            ///< MGMSG_MOT_MOVE_STOP: param1 channel, param2 stop mode
    kMotMoveStopped = 0x0466,         ///< MGMSG_MOT_MOVE_STOPPED, 14-byte status packet
    kMotReqUStatusUpdate = 0x0490,    ///< MGMSG_MOT_REQ_USTATUSUPDATE
    kMotGetUStatusUpdate = 0x0491,    ///< MGMSG_MOT_GET_USTATUSUPDATE, 14-byte status packet
};

/// Status bits of MGMSG_MOT_GET_USTATUSUPDATE / _STATUSBITS (protocol document, status-bit table).
enum StatusBit : std::uint32_t {
    kCwHardLimit = 0x00000001,
    kCcwHardLimit = 0x00000002,
    kMovingCw = 0x00000010,
    kMovingCcw = 0x00000020,
    kJoggingCw = 0x00000040,
    kJoggingCcw = 0x00000080,
    kHoming = 0x00000200,
    kHomed = 0x00000400,
    kMotionError = 0x00004000,  ///< excessive position error
    kCurrentLimit = 0x01000000,
    kChannelEnabled = 0x80000000,
};
inline constexpr std::uint32_t kMovingMask =
    kMovingCw | kMovingCcw | kJoggingCw | kJoggingCcw | kHoming;

/// Thorlabs K10CR1: 200 full steps × 2048 microsteps per motor turn through a 120:1 worm gear,
/// i.e. 409600 × 120 / 360 = 409600/3 microsteps per degree (136533.33), the value the protocol
/// document's position-scaling section gives for the K10CR1.
inline constexpr double kK10cr1CountsPerDegree = 409600.0 / 3.0;

/// One decoded message.
struct Message {
    std::uint16_t id = 0;
    std::uint8_t param1 = 0, param2 = 0;  ///< header-only messages
    std::uint8_t dest = 0, source = 0;    ///< dest without the 0x80 flag
    std::vector<std::uint8_t> data;       ///< data packet (empty for header-only messages)
    bool has_data() const { return !data.empty(); }
};

/// Encodes a header-only message.
std::vector<std::uint8_t> encode_short(std::uint16_t id, std::uint8_t param1, std::uint8_t param2,
                                       std::uint8_t dest = kUsbDeviceAddress,
                                       std::uint8_t source = kHostAddress);
/// Encodes a message with a data packet (sets dest | 0x80 and the length).
std::vector<std::uint8_t> encode_long(std::uint16_t id, std::span<const std::uint8_t> data,
                                      std::uint8_t dest = kUsbDeviceAddress,
                                      std::uint8_t source = kHostAddress);

std::vector<std::uint8_t> hw_req_info();
std::vector<std::uint8_t> hw_no_flash_programming();
std::vector<std::uint8_t> mod_identify(std::uint8_t channel = 1);
std::vector<std::uint8_t> mod_set_chan_enable_state(std::uint8_t channel, bool enable);
std::vector<std::uint8_t> mot_move_home(std::uint8_t channel = 1);
std::vector<std::uint8_t> mot_move_absolute(std::int32_t position, std::uint16_t channel = 1);
std::vector<std::uint8_t> mot_req_ustatus_update(std::uint8_t channel = 1);

/// Stop modes of MGMSG_MOT_MOVE_STOP (protocol document: "0x01 stop immediately (abrupt)",
/// "0x02 stop in a controlled (profiled) manner").
enum class StopMode : std::uint8_t { Immediate = 0x01, Profiled = 0x02 };
/// MGMSG_MOT_MOVE_STOP, header only: 65 04 <channel> <stop mode> <dest> <source>. Stops any move
/// (absolute, relative, homing, velocity); the controller answers MGMSG_MOT_MOVE_STOPPED.
std::vector<std::uint8_t> mot_move_stop(std::uint8_t channel = 1,
                                        StopMode mode = StopMode::Profiled);

/// Outcome of trying to decode the front of a byte stream.
enum class DecodeStatus { Complete, NeedMore, Invalid };
struct Decoded {
    DecodeStatus status = DecodeStatus::NeedMore;
    Message message;           ///< valid when Complete
    std::size_t consumed = 0;  ///< bytes used (Complete) or to skip to resynchronise (Invalid)
    std::string error;         ///< why Invalid
};
/// Decodes one message from the front of `bytes`. A header whose data length exceeds
/// `kMaxDataLength` is Invalid (protects against a misaligned stream).
Decoded decode(std::span<const std::uint8_t> bytes);
inline constexpr std::size_t kMaxDataLength = 255;

/// Decodes one host → controller message from the front of `bytes`, as a controller reads its
/// input: a header not addressed from the host (source 0x01) to `device_address` is Invalid with
/// `consumed` = 1, so a reader dropping that byte resynchronises on the next valid header after
/// garbage or bytes of another protocol (an Elliptec probe "0in" would otherwise shift every
/// following 6-byte header for good).
Decoded decode_host_request(std::span<const std::uint8_t> bytes,
                            std::uint8_t device_address = kUsbDeviceAddress);

/// MGMSG_HW_GET_INFO data packet (84 bytes): serial (int32), model (8 chars), type (u16),
/// firmware (minor, interim, major, unused), notes (48 chars), empty (12), hw version, mod state,
/// number of channels (u16 each).
struct HardwareInfo {
    std::uint32_t serial = 0;
    std::string model;
    std::uint16_t type = 0;
    int firmware_major = 0, firmware_interim = 0, firmware_minor = 0;
    std::string notes;
    std::uint16_t hardware_version = 0, mod_state = 0, channels = 0;
};
std::optional<HardwareInfo> parse_hw_info(const Message& m);
/// Encodes a HW_GET_INFO reply (used by the simulator).
std::vector<std::uint8_t> hw_get_info(const HardwareInfo& info,
                                      std::uint8_t source = kUsbDeviceAddress);

/// The 14-byte status packet of MOVE_COMPLETED, MOVE_STOPPED and GET_USTATUSUPDATE:
/// channel (u16), position (int32, microsteps), velocity (u16), motor current (int16), status bits
/// (u32).
struct StatusUpdate {
    std::uint16_t channel = 1;
    std::int32_t position = 0;
    std::uint16_t velocity = 0;
    std::int16_t motor_current = 0;
    std::uint32_t status_bits = 0;
};
std::optional<StatusUpdate> parse_status_update(const Message& m);
/// Encodes a status-packet message (`id` = MOVE_COMPLETED, MOVE_STOPPED or GET_USTATUSUPDATE).
std::vector<std::uint8_t> status_message(std::uint16_t id, const StatusUpdate& s,
                                         std::uint8_t source = kUsbDeviceAddress);

/// MGMSG_HW_RICHRESPONSE: message id the error refers to, error code, text (64 chars).
struct RichResponse {
    std::uint16_t message_id = 0, code = 0;
    std::string text;
};
std::optional<RichResponse> parse_rich_response(const Message& m);
std::vector<std::uint8_t> hw_rich_response(const RichResponse& r,
                                           std::uint8_t source = kUsbDeviceAddress);

/// Human-readable name of an id ("MGMSG_MOT_MOVE_HOMED") or "0x1234".
std::string message_name(std::uint16_t id);

}  // namespace tirpol::acquisition::apt
