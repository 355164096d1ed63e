// libusb implementation of the FtdiUsbIo seam (ftdi_port.h).

#include <fmt/format.h>
#include <libusb.h>

#include <thread>

#include "tirpol/acquisition/internal/ftdi_port.h"

namespace tirpol::acquisition {

namespace {

constexpr unsigned char kBulkOut = 0x02;  // FT232 endpoint addresses
constexpr unsigned char kBulkIn = 0x81;
// bmRequestType: vendor (0x40) | device recipient (0x00) | host-to-device (0x00).
constexpr std::uint8_t kVendorOut = 0x40;

DeviceError usb_error(const std::string& who, const char* what, int rc) {
    const auto code = rc == LIBUSB_ERROR_NO_DEVICE ? DeviceErrorCode::Disconnected
                      : rc == LIBUSB_ERROR_TIMEOUT ? DeviceErrorCode::Timeout
                                                   : DeviceErrorCode::IoError;
    return {code, fmt::format("{}: {} failed: {}", who, what,
                              libusb_strerror(static_cast<libusb_error>(rc)))};
}

class LibusbFtdiIo final : public FtdiUsbIo {
public:
    LibusbFtdiIo(libusb_context* ctx, libusb_device_handle* handle, std::string name,
                 std::size_t packet)
        : m_ctx(ctx), m_handle(handle), m_name(std::move(name)), m_packet(packet) {}
    ~LibusbFtdiIo() override {
        libusb_release_interface(m_handle, 0);
        libusb_close(m_handle);
        libusb_exit(m_ctx);
    }
    LibusbFtdiIo(const LibusbFtdiIo&) = delete;
    LibusbFtdiIo& operator=(const LibusbFtdiIo&) = delete;

    Status control_out(const FtdiControlRequest& r) override {
        const int rc = libusb_control_transfer(m_handle, kVendorOut, r.request, r.value, r.index,
                                               nullptr, 0, 1000);
        if (rc < 0) return usb_error(m_name, "control request", rc);
        return ok_status();
    }
    Status bulk_out(std::span<const std::uint8_t> bytes,
                    std::chrono::milliseconds timeout) override {
        std::vector<unsigned char> copy(bytes.begin(), bytes.end());
        int sent = 0;
        const int rc =
            libusb_bulk_transfer(m_handle, kBulkOut, copy.data(), static_cast<int>(copy.size()),
                                 &sent, static_cast<unsigned>(timeout.count()));
        if (rc < 0) return usb_error(m_name, "bulk write", rc);
        if (static_cast<std::size_t>(sent) != bytes.size())
            return DeviceError{DeviceErrorCode::Timeout,
                               fmt::format("{}: wrote {} of {} bytes", m_name, sent, bytes.size())};
        return ok_status();
    }
    Result<std::vector<std::uint8_t>> bulk_in(std::size_t max_bytes,
                                              std::chrono::milliseconds timeout) override {
        std::vector<std::uint8_t> buf(max_bytes);
        int got = 0;
        const int rc =
            libusb_bulk_transfer(m_handle, kBulkIn, buf.data(), static_cast<int>(buf.size()), &got,
                                 static_cast<unsigned>(std::max<long>(1, timeout.count())));
        if (rc == LIBUSB_ERROR_TIMEOUT) return std::vector<std::uint8_t>{};
        if (rc < 0) return usb_error(m_name, "bulk read", rc);
        buf.resize(static_cast<std::size_t>(got));
        return buf;
    }
    std::size_t max_packet_size() const override { return m_packet; }
    void dwell(std::chrono::milliseconds d) override { std::this_thread::sleep_for(d); }
    std::string name() const override { return m_name; }

private:
    libusb_context* m_ctx;
    libusb_device_handle* m_handle;
    std::string m_name;
    std::size_t m_packet;
};

std::string serial_of(libusb_device_handle* h, const libusb_device_descriptor& d) {
    unsigned char text[128] = {};
    if (d.iSerialNumber == 0) return "";
    const int n = libusb_get_string_descriptor_ascii(h, d.iSerialNumber, text, sizeof text);
    return n > 0 ? std::string(reinterpret_cast<char*>(text), static_cast<std::size_t>(n)) : "";
}

}  // namespace

Result<std::unique_ptr<BytePort>> open_ftdi_usb(const std::string& serial,
                                                const SerialSettings& settings,
                                                std::uint16_t product_id) {
    const std::string who = fmt::format("usb:{:04x}:{:04x}{}{}", kFtdiVendorId, product_id,
                                        serial.empty() ? "" : ":", serial);
    libusb_context* ctx = nullptr;
    if (int rc = libusb_init(&ctx); rc < 0) return usb_error(who, "libusb_init", rc);
    libusb_device** list = nullptr;
    const ssize_t count = libusb_get_device_list(ctx, &list);
    libusb_device_handle* found = nullptr;
    std::size_t packet = 64;
    for (ssize_t i = 0; i < count && !found; ++i) {
        libusb_device_descriptor d{};
        if (libusb_get_device_descriptor(list[i], &d) != 0 || d.idVendor != kFtdiVendorId ||
            d.idProduct != product_id)
            continue;
        libusb_device_handle* h = nullptr;
        if (libusb_open(list[i], &h) != 0) continue;
        if (serial.empty() || serial_of(h, d) == serial) {
            found = h;
            const int mps = libusb_get_max_packet_size(list[i], kBulkIn);
            if (mps > 0) packet = static_cast<std::size_t>(mps);
        } else {
            libusb_close(h);
        }
    }
    if (list) libusb_free_device_list(list, 1);
    if (!found) {
        libusb_exit(ctx);
        return DeviceError{
            DeviceErrorCode::Disconnected,
            fmt::format("{}: no such USB device (is it plugged in, and readable by this user?)",
                        who)};
    }
    // The kernel's ftdi_sio driver owns the interface by default; take it over for as long as we
    // hold it.
    libusb_set_auto_detach_kernel_driver(found, 1);
    if (int rc = libusb_claim_interface(found, 0); rc < 0) {
        libusb_close(found);
        libusb_exit(ctx);
        return usb_error(who, "claiming interface 0", rc);
    }
    return open_ftdi_port(std::make_unique<LibusbFtdiIo>(ctx, found, who, packet), settings);
}

}  // namespace tirpol::acquisition
