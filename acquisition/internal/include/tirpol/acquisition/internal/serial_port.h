#pragma once
/// \file serial_port.h
/// A POSIX serial port (termios): raw mode, 8 data bits, no parity, 1 stop bit, optional RTS/CTS
/// hardware flow control, non-blocking I/O with timeouts through poll(2). Works on USB-serial
/// adapters (the kernel's ftdi_sio driver: /dev/ttyUSB*) and on pseudo-terminals.

#include <filesystem>
#include <memory>

#include "tirpol/acquisition/internal/byte_port.h"

namespace tirpol::acquisition {

struct SerialSettings {
    int baud = 115200;     ///< one of the standard rates (9600 ... 921600)
    bool rts_cts = false;  ///< hardware flow control (APT controllers: on; Elliptec: off)
};

/// Opens and configures `path`. IoError/Disconnected/InvalidArgument (unsupported baud) on failure.
Result<std::unique_ptr<BytePort>> open_serial_port(const std::filesystem::path& path,
                                                   const SerialSettings& settings);

}  // namespace tirpol::acquisition
