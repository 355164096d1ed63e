#pragma once
/// \file elliptec_protocol.h
/// Thorlabs Elliptec (ELLx) ASCII protocol codec: pure functions over text, no I/O.
/// Source: Thorlabs, "Elliptec™ ELLx modules protocol manual" (Issue 7 and later), §2
/// "Communication protocol" and the per-command pages: host → module `<addr><cmd>[data]` with a
/// one-character hex address 0–F and a lower-case two-letter command; module → host
/// `<addr><CMD>[data]\r\n` with an upper-case reply code. Positions are 32-bit two's complement as
/// 8 upper-case hex digits. Serial settings: 9600 baud, 8 data bits, no parity, 1 stop bit, no flow
/// control.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace tirpol::acquisition::elliptec {

/// `<a>in`: get information (reply `IN`).
std::string info_request(char address);
/// `<a>ho<dir>`: home; dir 0 = clockwise, 1 = counter-clockwise (rotary stages). Reply `PO` when
/// done.
std::string home(char address, bool clockwise = true);
/// `<a>ma<8 hex>`: move absolute to `pulses`. Reply `PO` when done, `GS` on error/busy.
std::string move_absolute(char address, std::int32_t pulses);
/// `<a>gp`: get position (reply `PO`).
std::string get_position(char address);
/// `<a>gs`: get status (reply `GS` with a status code).
std::string get_status(char address);
/// `<a>st`: stop the motion now (manual, "_st_ stop"; reply `GS` with the status).
std::string stop(char address);

/// 8 upper-case hex digits, two's complement (manual: "position ... 32-bit signed, 8 hex digits").
std::string encode_position(std::int32_t pulses);
/// Inverse of encode_position; std::nullopt unless exactly 8 hex digits.
std::optional<std::int32_t> decode_position(std::string_view hex8);

/// A reply line without its CR LF.
struct Reply {
    char address = '0';
    std::string code;  ///< "IN", "PO", "GS", ...
    std::string data;
};
/// Parses `<addr><CODE><data>`; std::nullopt when the address is not 0–F or the code is not two
/// upper-case letters.
std::optional<Reply> parse_reply(std::string_view line);

/// The `IN` reply (manual, "_in_ get information"): motor type (2 hex), serial number (8),
/// year (4), firmware release (2 hex), thread/hardware (1 char thread: 0 metric, 1 imperial, then
/// 1 char hardware release), travel in the measurement unit (4 hex: mm or degrees), pulses over
/// that travel (8 hex; for a rotary mount, pulses per revolution).
struct DeviceInfo {
    int motor_type = 0;  ///< 14 for an ELL14 (0x0E)
    std::string serial, year;
    int firmware = 0;
    bool imperial_thread = false;
    int hardware_release = 0;
    std::uint32_t travel = 0;  ///< degrees for rotary mounts (360)
    std::uint32_t pulses = 0;  ///< pulses over `travel`
    /// Pulses per degree (rotary) or per mm (linear): pulses / travel.
    double pulses_per_unit() const { return travel ? static_cast<double>(pulses) / travel : 0.0; }
};
std::optional<DeviceInfo> parse_info(const Reply& reply);
/// Encodes the data part of an `IN` reply (used by the simulator).
std::string encode_info(const DeviceInfo& info);

/// Status codes of the `GS` reply (manual, "_gs_ get status" table).
enum StatusCode : int {
    kOk = 0,
    kCommunicationTimeout = 1,
    kMechanicalTimeout = 2,
    kCommandError = 3,
    kValueOutOfRange = 4,
    kModuleIsolated = 5,
    kModuleOutOfIsolation = 6,
    kInitializingError = 7,
    kThermalError = 8,
    kBusy = 9,
    kSensorError = 10,
    kMotorError = 11,
    kOutOfRange = 12,
    kOverCurrentError = 13,
};
/// Meaning of a status code as the manual words it ("Busy", "Mechanical time out", ...; 14–255
/// reserved).
std::string status_meaning(int code);
/// The status code in a `GS` reply's data (2 hex digits), std::nullopt if malformed.
std::optional<int> parse_status(const Reply& reply);

/// Removes and returns the first complete CR LF-terminated line from `buffer` (without CR LF).
std::optional<std::string> take_line(std::string& buffer);

/// Whether `c` is a valid module address (0–9, A–F).
bool valid_address(char c);

}  // namespace tirpol::acquisition::elliptec
