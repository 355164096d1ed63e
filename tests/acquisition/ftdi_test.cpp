// FTDI framing and set-up through the FtdiUsbIo seam (no USB bus on the test machines).
// Sources: Linux drivers/usb/serial/ftdi_sio.h (request codes, the FTDI_8U232AM_48MHz divisor
// table: 9600 → 0x4138, 115200 → 0x001a, ...; 2 status bytes at the start of each bulk-in packet),
// Thorlabs APT protocol document "USB device set-up" (115200 8N1, 50 ms dwells around the purge,
// reset, RTS/CTS flow control, RTS asserted).

#include <gtest/gtest.h>

#include <deque>

#include "tirpol/acquisition/internal/ftdi_port.h"

namespace tirpol::acquisition {
namespace {

using Bytes = std::vector<std::uint8_t>;

TEST(Ftdi, BaudDivisorsMatchTheKernelTable) {
    // ftdi_sio.h: FTDI_8U232AM_48MHz_b300 ... b921600 (every rate whose divisor the AM table and
    // the BM/R rounding agree on).
    const std::pair<int, std::uint32_t> table[] = {
        {300, 0x2710},    {600, 0x1388},    {1200, 0x09c4},   {2400, 0x04e2},
        {4800, 0x0271},   {9600, 0x4138},   {19200, 0x809c},  {38400, 0xc04e},
        {115200, 0x001a}, {230400, 0x000d}, {460800, 0x4006}, {921600, 0x8003}};
    for (const auto& [baud, divisor] : table) EXPECT_EQ(ftdi_baud_divisor(baud), divisor) << baud;
    // 57600: the AM table truncates 52.083 to 52 (0x0034); BM/R chips round to the nearest eighth,
    // 52 + 1/8, fraction code 3 in bits 14-15 (ftdi_232bm_baud_base_to_divisor) → 0xC034.
    EXPECT_EQ(ftdi_baud_divisor(57600), 0xC034u);
    EXPECT_EQ(ftdi_baud_divisor(3000000), 0u);  // special code for divisor 1
    EXPECT_EQ(ftdi_baud_divisor(2000000), 1u);  // and for 1.5
}

TEST(Ftdi, StatusBytesAreStrippedFromEveryPacket) {
    // Two full 64-byte packets and a short one; each starts with modem status 0x01 0x60.
    Bytes transfer;
    Bytes expected;
    std::uint8_t next = 0;
    for (std::size_t size : {64u, 64u, 10u}) {
        transfer.push_back(0x01);
        transfer.push_back(0x60);
        for (std::size_t i = 2; i < size; ++i) {
            transfer.push_back(next);
            expected.push_back(next++);
        }
    }
    Bytes out;
    ftdi_strip_status(transfer, 64, out);
    EXPECT_EQ(out, expected);
    out.clear();
    ftdi_strip_status(Bytes{0x01, 0x60}, 64, out);  // status only: no data
    EXPECT_TRUE(out.empty());
}

/// Test double: records what the port sends and replays scripted bulk-in transfers.
class RecordingFtdiUsb final : public FtdiUsbIo {
public:
    struct Log {
        std::vector<std::string> events;
        Bytes written;
        std::deque<Bytes> transfers;
    };
    explicit RecordingFtdiUsb(Log& log) : m_log(log) {}
    Status control_out(const FtdiControlRequest& r) override {
        m_log.events.push_back("ctrl " + std::to_string(r.request) + " " + std::to_string(r.value) +
                               " " + std::to_string(r.index));
        return ok_status();
    }
    Status bulk_out(std::span<const std::uint8_t> bytes, std::chrono::milliseconds) override {
        m_log.written.insert(m_log.written.end(), bytes.begin(), bytes.end());
        return ok_status();
    }
    Result<Bytes> bulk_in(std::size_t, std::chrono::milliseconds) override {
        if (m_log.transfers.empty())
            return DeviceError{DeviceErrorCode::Disconnected, "script exhausted"};
        Bytes t = m_log.transfers.front();
        m_log.transfers.pop_front();
        return t;
    }
    std::size_t max_packet_size() const override { return 64; }
    void dwell(std::chrono::milliseconds d) override {
        m_log.events.push_back("dwell " + std::to_string(d.count()));
    }
    std::string name() const override { return "fake-ftdi"; }

private:
    Log& m_log;
};

TEST(Ftdi, OpeningProgramsTheChipInTheOrderThorlabsAsks) {
    RecordingFtdiUsb::Log log;
    auto port =
        open_ftdi_port(std::make_unique<RecordingFtdiUsb>(log), SerialSettings{115200, true});
    ASSERT_TRUE(port);
    const std::vector<std::string> expected = {
        "ctrl 3 26 0",   // baud 115200 → divisor 0x001A
        "ctrl 4 8 0",    // 8 data bits, no parity, 1 stop bit
        "dwell 50",      // pre-purge dwell
        "ctrl 0 1 0",    // purge RX
        "ctrl 0 2 0",    // purge TX
        "dwell 50",      // post-purge dwell
        "ctrl 0 0 0",    // reset
        "ctrl 2 0 256",  // RTS/CTS flow control (0x0100 in wIndex)
        "ctrl 1 514 0",  // RTS high (0x0202)
    };
    EXPECT_EQ(log.events, expected);
}

TEST(Ftdi, PortDeliversOnlyPayloadAndSkipsEmptyStatusPackets) {
    RecordingFtdiUsb::Log log;
    auto port =
        open_ftdi_port(std::make_unique<RecordingFtdiUsb>(log), SerialSettings{115200, true});
    ASSERT_TRUE(port);
    // The chip answers with bare status packets until data arrives (latency timer).
    log.transfers = {Bytes{0x01, 0x60}, Bytes{0x01, 0x60},
                     Bytes{0x01, 0x60, 0x44, 0x04, 0x01, 0x00, 0x01, 0x50}};
    auto bytes = port.value()->read_some(std::chrono::milliseconds(1000));
    ASSERT_TRUE(bytes);
    EXPECT_EQ(bytes.value(),
              (Bytes{0x44, 0x04, 0x01, 0x00, 0x01, 0x50}));  // MOVE_HOMED, no status bytes
    ASSERT_TRUE(port.value()->write(Bytes{0x43, 0x04, 0x01, 0x00, 0x50, 0x01},
                                    std::chrono::milliseconds(100)));
    EXPECT_EQ(log.written, (Bytes{0x43, 0x04, 0x01, 0x00, 0x50, 0x01}));  // bulk out is not framed
    auto gone = port.value()->read_some(std::chrono::milliseconds(1000));
    ASSERT_FALSE(gone);
    EXPECT_EQ(gone.error().code, DeviceErrorCode::Disconnected);
}

}  // namespace
}  // namespace tirpol::acquisition
