#include "camera/gvcp_probe.h"

#include <arpa/inet.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdint>

namespace tirpol::acquisition::gvcp {

namespace {
constexpr std::uint8_t kCommandKey = 0x42;
constexpr std::uint8_t kAckRequired = 0x01;
constexpr std::uint16_t kReadRegisterCmd = 0x0080;
constexpr std::uint16_t kReadRegisterAck = 0x0081;

/// Closes the socket on every path out.
struct Socket {
    int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    ~Socket() {
        if (fd >= 0) ::close(fd);
    }
};
}  // namespace

ProbeResult probe_register(const sockaddr_in& device, std::uint32_t register_address,
                           std::chrono::milliseconds timeout_each, int tries) {
    Socket s;
    // connect(): the kernel then reports ICMP errors for this peer as ECONNREFUSED on recv.
    if (s.fd < 0 || ::connect(s.fd, reinterpret_cast<const sockaddr*>(&device), sizeof device) != 0)
        return ProbeResult::Silent;
    for (int attempt = 0; attempt < tries; ++attempt) {
        const auto id =
            static_cast<std::uint16_t>(0x7A00 + attempt);  // any non-zero id; echoed in the ack
        std::array<std::uint8_t, 12> cmd{kCommandKey,
                                         kAckRequired,
                                         kReadRegisterCmd >> 8,
                                         kReadRegisterCmd & 0xFF,
                                         0,
                                         4,
                                         static_cast<std::uint8_t>(id >> 8),
                                         static_cast<std::uint8_t>(id & 0xFF)};
        for (std::size_t i = 0; i < 4; ++i)
            cmd[8 + i] = static_cast<std::uint8_t>(register_address >> (24 - 8 * i));
        if (::send(s.fd, cmd.data(), cmd.size(), 0) < 0) {
            if (errno == ECONNREFUSED) return ProbeResult::Refused;
            continue;
        }
        const auto deadline = std::chrono::steady_clock::now() + timeout_each;
        for (;;) {
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                deadline - std::chrono::steady_clock::now());
            if (left.count() <= 0) break;
            pollfd p{s.fd, POLLIN, 0};
            if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) continue;
            std::array<std::uint8_t, 64> ack{};
            const ssize_t n = ::recv(s.fd, ack.data(), ack.size(), 0);
            if (n < 0 && errno == ECONNREFUSED) return ProbeResult::Refused;
            const bool is_ack = n >= 12 && ((ack[2] << 8) | ack[3]) == kReadRegisterAck &&
                                ((ack[6] << 8) | ack[7]) == id;
            if (is_ack) return ProbeResult::Answered;
        }
    }
    return ProbeResult::Silent;
}

}  // namespace tirpol::acquisition::gvcp
