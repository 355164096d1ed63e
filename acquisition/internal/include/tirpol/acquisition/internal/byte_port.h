#pragma once
/// \file byte_port.h
/// A byte stream to a device (the transport under a protocol codec): a POSIX serial port
/// (serial_port.h) or an FTDI chip driven through libusb (ftdi_port.h). Failures are values.

#include <chrono>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "tirpol/acquisition/result.h"

namespace tirpol::acquisition {

class BytePort {
public:
    virtual ~BytePort() = default;
    /// Writes all of `bytes` within `timeout`.
    virtual Status write(std::span<const std::uint8_t> bytes,
                         std::chrono::milliseconds timeout) = 0;
    /// Returns the bytes available now, waiting up to `timeout` for at least one.
    /// Timeout error if none arrive; Disconnected if the device went away.
    virtual Result<std::vector<std::uint8_t>> read_some(std::chrono::milliseconds timeout) = 0;
    /// Discards bytes received but not yet read.
    virtual Status discard_input() = 0;
    /// "/dev/ttyUSB0", "usb:55000123", ... for messages.
    virtual std::string name() const = 0;
};

}  // namespace tirpol::acquisition
