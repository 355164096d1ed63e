#pragma once
/// \file fluke_scpi.h
/// Codec of the serial protocol of the Fluke Calibration 4180/4181 Precision Infrared Calibrators
/// (Users/Operators Manual, chapter "Digital Communication Interface": "Serial Operation", "Command
/// Syntax", "Serial Commands - Alphabetic Listing"). ASCII, SCPI-1994 style, 8 data bits, no
/// parity, 1 stop bit; a command ends with CR or LF, mnemonics are case-insensitive and have a long
/// and a short form, no compound commands; a query's reply is one line. Pure functions over text;
/// the driver (fluke_blackbody.cpp) and the simulator (blackbody_simulator.cpp) share them. Which
/// commands come from where: docs/acquisition-blackbody.md.

#include <optional>
#include <string>
#include <string_view>

namespace tirpol::acquisition::fluke_scpi {

inline constexpr int kDefaultBaud = 9600;
/// 4180 set-point range −15 … 120 °C; 4181 35 … 500 °C (product specifications).
inline constexpr double kModel4180MinC = -15.0, kModel4180MaxC = 120.0;
inline constexpr double kModel4181MinC = 35.0, kModel4181MaxC = 500.0;

// Commands as the driver sends them (short forms, LF-terminated).
inline constexpr std::string_view kIdentify = "*IDN?\n";
inline constexpr std::string_view kClearStatus = "*CLS\n";
inline constexpr std::string_view kUnitsCelsius = "UNIT:TEMP C\n";
inline constexpr std::string_view kReadTemperature = "SOUR:SENS:DATA?\n";
inline constexpr std::string_view kReadSetPoint = "SOUR:SPO?\n";
inline constexpr std::string_view kReadStability = "SOUR:STAB:TEST?\n";
inline constexpr std::string_view kReadCutoutTripped = "SOUR:PROT:TRIP?\n";
inline constexpr std::string_view kReadError = "SYST:ERR?\n";
/// "SOUR:SPO 35.000\n" (°C, millikelvin resolution).
std::string set_point_command(double set_point_c);
/// "SOUR:STAB:LIM 0.050\n" (°C).
std::string stability_limit_command(double limit_c);

/// A command header in canonical short form, upper case: "sour:spoint" and "SOURce:SPOint" →
/// "SOUR:SPO"; a trailing '?' is kept. A mnemonic that is neither the long nor the short form of a
/// known keyword is returned upper-cased as it is (the device then answers "Undefined header").
std::string canonical_header(std::string_view header);

/// A number reply ("35.012", "+3.5012E+01"); nullopt for anything else (a garbled reply).
std::optional<double> parse_number(std::string_view reply);
/// A boolean reply "0" / "1".
std::optional<bool> parse_flag(std::string_view reply);

/// An error-queue entry: `0,"No error"`, `-113,"Undefined header"`.
struct ErrorEntry {
    int code = 0;
    std::string message;
};
std::optional<ErrorEntry> parse_error(std::string_view reply);
std::string format_error(const ErrorEntry& entry);

/// "*IDN?" reply: "FLUKE,4180,B12345,1.10" → manufacturer, model, serial, firmware.
struct Identity {
    std::string manufacturer, model, serial, firmware;
};
std::optional<Identity> parse_identity(std::string_view reply);

}  // namespace tirpol::acquisition::fluke_scpi
