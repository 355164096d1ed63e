#include "tirpol/acquisition/internal/ftdi_port.h"

#include <fmt/format.h>

#include <algorithm>

namespace tirpol::acquisition {

std::uint32_t ftdi_baud_divisor(int baud) {
    // Index = eighths of the divisor, value = the chip's code for that fraction (ftdi_sio.c
    // ftdi_232bm_baud_base_to_divisor).
    static constexpr std::uint32_t kFractionCode[8] = {0, 3, 2, 4, 1, 5, 6, 7};
    constexpr std::uint32_t kBase = 3000000;
    const std::uint32_t eighths =
        (kBase * 8u + static_cast<std::uint32_t>(baud) / 2u) / static_cast<std::uint32_t>(baud);
    std::uint32_t divisor = (eighths >> 3) | (kFractionCode[eighths & 7] << 14);
    // Divisors 1 and 1.5 have special codes (3 MHz and 2 MHz).
    if (divisor == 1)
        divisor = 0;
    else if (divisor == 0x4001)
        divisor = 1;
    return divisor;
}

std::vector<FtdiControlRequest> ftdi_setup_sequence(const SerialSettings& settings) {
    const std::uint32_t divisor = ftdi_baud_divisor(settings.baud);
    // Single-interface chips (FT232BM/R in the APT controllers) take interface index 0, as the
    // kernel driver sends.
    return {
        {kFtdiBaudRate, static_cast<std::uint16_t>(divisor & 0xFFFF),
         static_cast<std::uint16_t>(divisor >> 16)},
        {kFtdiLineSettings, 0x0008, 0},  // 8 data bits, no parity (0 << 8), 1 stop bit (0 << 11)
        {kFtdiReset, 1, 0},              // purge RX
        {kFtdiReset, 2, 0},              // purge TX
        {kFtdiReset, 0, 0},              // reset SIO
        {kFtdiFlowControl, 0, static_cast<std::uint16_t>(settings.rts_cts ? 0x0100 : 0x0000)},
        {kFtdiModemControl, 0x0202, 0},  // RTS high
    };
}

void ftdi_strip_status(std::span<const std::uint8_t> transfer, std::size_t packet_size,
                       std::vector<std::uint8_t>& out) {
    for (std::size_t at = 0; at < transfer.size(); at += packet_size) {
        const std::size_t end = std::min(transfer.size(), at + packet_size);
        if (end - at > 2)
            out.insert(out.end(), transfer.begin() + static_cast<std::ptrdiff_t>(at + 2),
                       transfer.begin() + static_cast<std::ptrdiff_t>(end));
    }
}

namespace {

class FtdiPort final : public BytePort {
public:
    explicit FtdiPort(std::unique_ptr<FtdiUsbIo> io) : m_io(std::move(io)) {}

    Status write(std::span<const std::uint8_t> bytes, std::chrono::milliseconds timeout) override {
        return m_io->bulk_out(bytes, timeout);
    }

    Result<std::vector<std::uint8_t>> read_some(std::chrono::milliseconds timeout) override {
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        // The chip answers every bulk-in with at least its 2 status bytes (after its latency
        // timer), so an answer with no payload is "nothing yet": keep asking until the deadline.
        for (;;) {
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                deadline - std::chrono::steady_clock::now());
            if (left.count() <= 0)
                return DeviceError{
                    DeviceErrorCode::Timeout,
                    fmt::format("{}: no reply within {} ms", m_io->name(), timeout.count())};
            auto transfer = m_io->bulk_in(m_io->max_packet_size() * 8, left);
            if (!transfer) return transfer.error();
            std::vector<std::uint8_t> payload;
            ftdi_strip_status(transfer.value(), m_io->max_packet_size(), payload);
            if (!payload.empty()) return payload;
        }
    }

    Status discard_input() override { return m_io->control_out({kFtdiReset, 1, 0}); }
    std::string name() const override { return m_io->name(); }

private:
    std::unique_ptr<FtdiUsbIo> m_io;
};

}  // namespace

Result<std::unique_ptr<BytePort>> open_ftdi_port(std::unique_ptr<FtdiUsbIo> io,
                                                 const SerialSettings& settings) {
    if (settings.baud <= 0 || settings.baud > 3000000)
        return DeviceError{DeviceErrorCode::InvalidArgument,
                           fmt::format("{}: unsupported baud rate {}", io->name(), settings.baud)};
    for (const auto& request : ftdi_setup_sequence(settings)) {
        // Thorlabs: "pre purge dwell 50 ms, purge the device, post purge dwell 50 ms".
        const bool purge = request.request == kFtdiReset && request.value != 0;
        if (purge && request.value == 1) io->dwell(std::chrono::milliseconds(50));
        if (auto status = io->control_out(request); !status) return status.error();
        if (purge && request.value == 2) io->dwell(std::chrono::milliseconds(50));
    }
    return std::unique_ptr<BytePort>(std::make_unique<FtdiPort>(std::move(io)));
}

}  // namespace tirpol::acquisition
