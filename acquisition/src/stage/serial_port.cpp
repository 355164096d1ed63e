#include "tirpol/acquisition/internal/serial_port.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace tirpol::acquisition {

namespace {

speed_t speed_for(int baud) {
    switch (baud) {
        case 9600:
            return B9600;
        case 19200:
            return B19200;
        case 38400:
            return B38400;
        case 57600:
            return B57600;
        case 115200:
            return B115200;
        case 230400:
            return B230400;
        case 460800:
            return B460800;
        case 921600:
            return B921600;
        default:
            return B0;
    }
}

int remaining_ms(std::chrono::steady_clock::time_point deadline) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    return left.count() > 0 ? static_cast<int>(left.count()) : 0;
}

class SerialPort final : public BytePort {
public:
    SerialPort(int fd, std::string name) : m_fd(fd), m_name(std::move(name)) {}
    ~SerialPort() override { ::close(m_fd); }
    SerialPort(const SerialPort&) = delete;
    SerialPort& operator=(const SerialPort&) = delete;

    Status write(std::span<const std::uint8_t> bytes, std::chrono::milliseconds timeout) override {
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        std::size_t done = 0;
        while (done < bytes.size()) {
            const ssize_t n = ::write(m_fd, bytes.data() + done, bytes.size() - done);
            if (n > 0) {
                done += static_cast<std::size_t>(n);
                continue;
            }
            if (n < 0 && errno == EINTR) continue;
            if (n < 0 && errno != EAGAIN) return os_error("write");
            pollfd p{m_fd, POLLOUT, 0};
            const int rc = ::poll(&p, 1, remaining_ms(deadline));
            if (rc == 0)
                return DeviceError{DeviceErrorCode::Timeout,
                                   fmt::format("{}: write blocked (flow control?) for {} ms",
                                               m_name, timeout.count())};
            if (rc < 0 && errno != EINTR) return os_error("poll");
            if (p.revents & (POLLHUP | POLLERR)) return hangup();
        }
        return ok_status();
    }

    Result<std::vector<std::uint8_t>> read_some(std::chrono::milliseconds timeout) override {
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        for (;;) {
            std::uint8_t buf[512];
            const ssize_t n = ::read(m_fd, buf, sizeof buf);
            if (n > 0) return std::vector<std::uint8_t>(buf, buf + n);
            if (n == 0) return hangup();
            if (errno == EINTR) continue;
            // A pseudo-terminal whose other end closed reads EIO: the device went away.
            if (errno == EIO) return hangup();
            if (errno != EAGAIN) return os_error("read");
            const int wait = remaining_ms(deadline);
            if (wait == 0)
                return DeviceError{
                    DeviceErrorCode::Timeout,
                    fmt::format("{}: no reply within {} ms", m_name, timeout.count())};
            pollfd p{m_fd, POLLIN, 0};
            const int rc = ::poll(&p, 1, wait);
            if (rc < 0 && errno != EINTR) return os_error("poll");
            if (rc > 0 && (p.revents & (POLLHUP | POLLERR)) && !(p.revents & POLLIN))
                return hangup();
        }
    }

    Status discard_input() override {
        if (::tcflush(m_fd, TCIFLUSH) != 0) return os_error("tcflush");
        return ok_status();
    }

    std::string name() const override { return m_name; }

private:
    DeviceError os_error(const char* what) const {
        return {DeviceErrorCode::IoError,
                fmt::format("{}: {} failed: {}", m_name, what, std::strerror(errno))};
    }
    DeviceError hangup() const {
        return {DeviceErrorCode::Disconnected,
                fmt::format("{}: the device hung up (cable pulled or power lost?)", m_name)};
    }
    int m_fd;
    std::string m_name;
};

}  // namespace

Result<std::unique_ptr<BytePort>> open_serial_port(const std::filesystem::path& path,
                                                   const SerialSettings& settings) {
    const speed_t speed = speed_for(settings.baud);
    if (speed == B0)
        return DeviceError{
            DeviceErrorCode::InvalidArgument,
            fmt::format("{}: unsupported baud rate {}", path.string(), settings.baud)};
    const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        const auto code = (errno == ENOENT || errno == ENXIO || errno == ENODEV)
                              ? DeviceErrorCode::Disconnected
                              : DeviceErrorCode::IoError;
        return DeviceError{code,
                           fmt::format("{}: cannot open: {}", path.string(), std::strerror(errno))};
    }
    termios tio{};
    if (::tcgetattr(fd, &tio) != 0) {
        const int err = errno;
        ::close(fd);
        return DeviceError{
            DeviceErrorCode::IoError,
            fmt::format("{}: not a serial port: {}", path.string(), std::strerror(err))};
    }
    ::cfmakeraw(&tio);
    tio.c_cflag &= ~static_cast<tcflag_t>(CSIZE | PARENB | CSTOPB | CRTSCTS);
    tio.c_cflag |= CS8 | CLOCAL | CREAD;
    if (settings.rts_cts) tio.c_cflag |= CRTSCTS;
    // VMIN 1 with O_NONBLOCK: an empty read fails with EAGAIN, so a read of 0 bytes means hang-up
    // (with VMIN 0 the tty layer would return 0 for "no data" too).
    tio.c_cc[VMIN] = 1;
    tio.c_cc[VTIME] = 0;
    ::cfsetispeed(&tio, speed);
    ::cfsetospeed(&tio, speed);
    if (::tcsetattr(fd, TCSANOW, &tio) != 0) {
        const int err = errno;
        ::close(fd);
        return DeviceError{DeviceErrorCode::IoError,
                           fmt::format("{}: cannot configure {} 8N1: {}", path.string(),
                                       settings.baud, std::strerror(err))};
    }
    ::tcflush(fd, TCIOFLUSH);
    if (settings.rts_cts) {
        // Thorlabs asks hosts to assert RTS after configuring the port. A pseudo-terminal has no
        // modem lines (ENOTTY/EINVAL): nothing to assert there, so the result is not an error.
        int rts = TIOCM_RTS;
        ::ioctl(fd, TIOCMBIS, &rts);
    }
    return std::unique_ptr<BytePort>(std::make_unique<SerialPort>(fd, path.string()));
}

}  // namespace tirpol::acquisition
