#include <fcntl.h>
#include <fmt/format.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <utility>

#include "tirpol/acquisition/sim/stage_simulator.h"

namespace tirpol::acquisition {

PseudoTerminal::PseudoTerminal(int master, int slave, std::string path)
    : m_master(master), m_slave_keepalive(slave), m_slave_path(std::move(path)) {}
PseudoTerminal::PseudoTerminal(PseudoTerminal&& o) noexcept
    : m_master(std::exchange(o.m_master, -1)),
      m_slave_keepalive(std::exchange(o.m_slave_keepalive, -1)),
      m_slave_path(std::move(o.m_slave_path)) {}
PseudoTerminal& PseudoTerminal::operator=(PseudoTerminal&& o) noexcept {
    if (this != &o) {
        hang_up();
        m_master = std::exchange(o.m_master, -1);
        m_slave_keepalive = std::exchange(o.m_slave_keepalive, -1);
        m_slave_path = std::move(o.m_slave_path);
    }
    return *this;
}
PseudoTerminal::~PseudoTerminal() { hang_up(); }

void PseudoTerminal::hang_up() {
    if (m_slave_keepalive >= 0) ::close(m_slave_keepalive);
    if (m_master >= 0) ::close(m_master);
    m_slave_keepalive = m_master = -1;
}

Result<PseudoTerminal> PseudoTerminal::open() {
    const int master = ::posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (master < 0)
        return DeviceError{DeviceErrorCode::IoError,
                           fmt::format("posix_openpt failed: {}", std::strerror(errno))};
    char name[128];
    if (::grantpt(master) != 0 || ::unlockpt(master) != 0 ||
        ::ptsname_r(master, name, sizeof name) != 0) {
        const int err = errno;
        ::close(master);
        return DeviceError{
            DeviceErrorCode::IoError,
            fmt::format("setting up the pseudo-terminal failed: {}", std::strerror(err))};
    }
    const int slave = ::open(name, O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (slave < 0) {
        const int err = errno;
        ::close(master);
        return DeviceError{DeviceErrorCode::IoError,
                           fmt::format("{}: cannot open: {}", name, std::strerror(err))};
    }
    // Raw from the start: no echo or line editing before the driver configures the port.
    termios tio{};
    ::tcgetattr(slave, &tio);
    ::cfmakeraw(&tio);
    ::tcsetattr(slave, TCSANOW, &tio);
    ::fcntl(master, F_SETFL, ::fcntl(master, F_GETFL) | O_NONBLOCK);
    return PseudoTerminal(master, slave, name);
}

void serve_pty_device(PtyDevice& device, PseudoTerminal& pty, const std::atomic<bool>& stop) {
    auto write_all = [&](const std::vector<std::uint8_t>& bytes) {
        std::size_t done = 0;
        while (done < bytes.size()) {
            const ssize_t n = ::write(pty.master_fd(), bytes.data() + done, bytes.size() - done);
            if (n > 0)
                done += static_cast<std::size_t>(n);
            else if (n < 0 && errno != EAGAIN && errno != EINTR)
                return;
            else
                ::usleep(1000);
        }
    };
    while (!stop.load()) {
        const auto now = PtyDevice::Clock::now();
        if (device.hang_up(now)) {
            pty.hang_up();
            return;
        }
        write_all(device.poll(now));
        pollfd p{pty.master_fd(), POLLIN, 0};
        if (::poll(&p, 1, 2) > 0 && (p.revents & POLLIN)) {
            std::uint8_t buf[256];
            const ssize_t n = ::read(pty.master_fd(), buf, sizeof buf);
            if (n > 0)
                write_all(
                    device.receive(std::span<const std::uint8_t>(buf, static_cast<std::size_t>(n)),
                                   PtyDevice::Clock::now()));
        }
    }
}

namespace {
std::atomic<bool> g_stop_program{false};
extern "C" void on_simulator_stop_signal(int) { g_stop_program = true; }
}  // namespace

int run_pty_simulator_program(PtyDevice& device, const std::string& link, const char* program) {
    auto pty = PseudoTerminal::open();
    if (!pty) {
        std::fprintf(stderr, "%s: %s\n", program, pty.error().message.c_str());
        return 1;
    }
    if (!link.empty()) {
        std::error_code ec;
        std::filesystem::remove(link, ec);
        std::filesystem::create_symlink(pty.value().slave_path(), link, ec);
        if (ec) {
            std::fprintf(stderr, "%s: cannot link %s: %s\n", program, link.c_str(),
                         ec.message().c_str());
            return 1;
        }
    }
    std::signal(SIGINT, on_simulator_stop_signal);
    std::signal(SIGTERM, on_simulator_stop_signal);
    std::printf("%s\n", pty.value().slave_path().c_str());
    std::fflush(stdout);
    serve_pty_device(device, pty.value(), g_stop_program);
    if (!link.empty()) {
        std::error_code ec;
        std::filesystem::remove(link, ec);
    }
    return 0;
}

}  // namespace tirpol::acquisition
