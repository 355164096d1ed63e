#pragma once
/// \file ftdi_port.h
/// A byte port straight to an FTDI USB-serial chip through libusb, bypassing the kernel's ftdi_sio
/// driver (Thorlabs APT controllers enumerate as FTDI 0403:faf0, Linux ftdi_sio_ids.h
/// FTDI_THORLABS_PID). The chip is programmed with vendor control requests (bmRequestType 0x40):
/// 0 reset/purge, 1 modem control, 2 flow control, 3 baud-rate divisor, 4 line settings (Linux
/// drivers/usb/serial/ftdi_sio.h documents each). Every bulk-in packet (max packet size, 64 bytes
/// at full speed) starts with 2 modem/line status bytes that are not data.
///
/// The USB side is behind `FtdiUsbIo` (the seam) so the framing and the control sequence are tested
/// without a USB bus; `open_ftdi_usb` provides the libusb implementation.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tirpol/acquisition/internal/byte_port.h"
#include "tirpol/acquisition/internal/serial_port.h"

namespace tirpol::acquisition {

inline constexpr std::uint16_t kFtdiVendorId = 0x0403;
inline constexpr std::uint16_t kThorlabsAptProductId = 0xFAF0;

/// bRequest values of the FTDI vendor control requests (Linux ftdi_sio.h FTDI_SIO_*).
enum FtdiRequest : std::uint8_t {
    kFtdiReset = 0,         ///< wValue 0 reset, 1 purge RX, 2 purge TX
    kFtdiModemControl = 1,  ///< wValue = (mask << 8) | state; 0x0202 = RTS high, 0x0101 = DTR high
    kFtdiFlowControl = 2,   ///< wIndex high byte: 0x01 RTS/CTS, 0x02 DTR/DSR, 0x04 XON/XOFF
    kFtdiBaudRate = 3,      ///< wValue/wIndex = the encoded divisor (ftdi_baud_divisor)
    kFtdiLineSettings = 4,  ///< wValue = data bits | parity << 8 | stop bits << 11
};

struct FtdiControlRequest {
    std::uint8_t request = 0;
    std::uint16_t value = 0, index = 0;
    bool operator==(const FtdiControlRequest&) const = default;
};

/// The encoded baud-rate divisor of FT232BM/R chips (3 MHz reference): 14-bit integer divisor, and
/// the fraction in eighths 0..7 coded {0, 3, 2, 4, 1, 5, 6, 7} in bits 14–16 (Linux ftdi_sio.c,
/// ftdi_232bm_baud_base_to_divisor). Low 16 bits go in wValue, bit 16 in wIndex. E.g. 115200 →
/// 0x001A, 9600 → 0x4138 (ftdi_sio.h table).
std::uint32_t ftdi_baud_divisor(int baud);

/// The control requests that bring the chip up for `settings`, in order, as the Thorlabs APT
/// protocol document's "USB device set-up" asks: baud rate, 8N1, purge RX and TX (with a 50 ms
/// dwell before and after, done by FtdiPort), reset, flow control, RTS asserted.
std::vector<FtdiControlRequest> ftdi_setup_sequence(const SerialSettings& settings);

/// Appends the payload of a bulk-in transfer to `out`, dropping the 2 status bytes at the start
/// of every `packet_size` chunk.
void ftdi_strip_status(std::span<const std::uint8_t> transfer, std::size_t packet_size,
                       std::vector<std::uint8_t>& out);

/// The USB operations an FTDI port needs (the test seam).
class FtdiUsbIo {
public:
    virtual ~FtdiUsbIo() = default;
    virtual Status control_out(const FtdiControlRequest& request) = 0;
    virtual Status bulk_out(std::span<const std::uint8_t> bytes,
                            std::chrono::milliseconds timeout) = 0;
    /// One bulk-in transfer of up to `max_bytes` (status bytes included); empty on a timeout.
    virtual Result<std::vector<std::uint8_t>> bulk_in(std::size_t max_bytes,
                                                      std::chrono::milliseconds timeout) = 0;
    virtual std::size_t max_packet_size() const = 0;
    virtual void dwell(std::chrono::milliseconds duration) = 0;
    virtual std::string name() const = 0;
};

/// Configures the chip through `io` (ftdi_setup_sequence) and returns a port over it.
Result<std::unique_ptr<BytePort>> open_ftdi_port(std::unique_ptr<FtdiUsbIo> io,
                                                 const SerialSettings& settings);

/// Finds the FTDI device 0403:`product_id` whose USB serial number is `serial` (any when empty)
/// with libusb, claims interface 0 and opens it as a port.
Result<std::unique_ptr<BytePort>> open_ftdi_usb(const std::string& serial,
                                                const SerialSettings& settings,
                                                std::uint16_t product_id = kThorlabsAptProductId);

}  // namespace tirpol::acquisition
