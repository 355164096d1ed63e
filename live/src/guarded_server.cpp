#include "guarded_server.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <functional>
#include <thread>

namespace tirpol::live::detail {

namespace {
using Clock = std::chrono::steady_clock;

/// Waits are cut into slices so that a stopping server ends its connections promptly.
constexpr std::chrono::milliseconds kWaitSlice{100};
/// After a refusal, how long the bytes a client is still sending are read and discarded before the
/// socket closes, so that the close does not reset the connection before the client read the
/// answer.
constexpr std::chrono::milliseconds kLingerTime{300};
constexpr std::size_t kLingerBytes = 256 * 1024;
/// Chunk-size lines and trailers of a chunked body, on top of the body limit.
constexpr std::size_t kChunkFramingBytes = 8 * 1024;
constexpr std::size_t kKeepAliveRequests = 100;

thread_local bool t_close_after_request = false;

void address_of(const sockaddr_storage& addr, std::string& ip, int& port) {
    std::array<char, INET6_ADDRSTRLEN> text{};
    if (addr.ss_family == AF_INET) {
        const auto* a = reinterpret_cast<const sockaddr_in*>(&addr);
        ::inet_ntop(AF_INET, &a->sin_addr, text.data(), text.size());
        port = ntohs(a->sin_port);
    } else if (addr.ss_family == AF_INET6) {
        const auto* a = reinterpret_cast<const sockaddr_in6*>(&addr);
        ::inet_ntop(AF_INET6, &a->sin6_addr, text.data(), text.size());
        port = ntohs(a->sin6_port);
    }
    ip = text.data();
}

/// A socket read through a buffer, with a byte budget and deadlines per request: the head (request
/// line and headers, up to the blank line) at most `max_head_bytes` within `head_timeout` of its
/// first byte, the body at most the body limit, the request and its answer within
/// `request_timeout`. A read past a budget or a deadline fails (-1), which ends the request and the
/// connection.
class BoundedStream final : public httplib::Stream {
public:
    BoundedStream(socket_t sock, const RequestLimits& limits, std::function<bool()> stopping)
        : m_sock(sock), m_limits(limits), m_stopping(std::move(stopping)) {}

    /// Waits up to `idle` for the next request's first byte; false when none came or the server
    /// stops.
    bool wait_for_request(std::chrono::milliseconds idle) {
        if (m_begin < m_end) return true;
        return wait(POLLIN, Clock::now() + idle) && fill() > 0;
    }

    void begin_request() {
        const auto now = Clock::now();
        m_head_deadline = now + m_limits.head_timeout;
        m_request_deadline = now + m_limits.request_timeout;
        m_head_bytes = m_body_bytes = 0;
        m_in_body = false;
        m_tail = 0;
    }

    bool is_readable() const override { return m_begin < m_end || wait(POLLIN, read_deadline()); }
    bool is_writable() const override { return wait(POLLOUT, m_request_deadline); }

    ssize_t read(char* ptr, size_t size) override {
        if (m_begin == m_end && (!wait(POLLIN, read_deadline()) || fill() <= 0)) return -1;
        std::size_t n = std::min(size, m_end - m_begin);
        if (!m_in_body) {
            // Count head bytes one at a time up to the blank line that ends the headers.
            std::size_t i = 0;
            while (i < n && !m_in_body) {
                m_tail = (m_tail << 8) | static_cast<unsigned char>(m_buffer[m_begin + i]);
                ++i;
                if (++m_head_bytes > m_limits.max_head_bytes) return -1;
                if ((m_tail & 0xffffffffu) == 0x0d0a0d0au) m_in_body = true;
            }
            n = i;
        } else {
            m_body_bytes += n;
            if (m_body_bytes > m_limits.max_body_bytes + kChunkFramingBytes) return -1;
        }
        std::copy_n(m_buffer.data() + m_begin, n, ptr);
        m_begin += n;
        return static_cast<ssize_t>(n);
    }

    ssize_t write(const char* ptr, size_t size) override {
        std::size_t sent = 0;
        while (sent < size) {
            if (!wait(POLLOUT, m_request_deadline)) return -1;
            const ssize_t n = ::send(m_sock, ptr + sent, size - sent, MSG_NOSIGNAL);
            if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
            if (n <= 0) return -1;
            sent += static_cast<std::size_t>(n);
        }
        return static_cast<ssize_t>(sent);
    }

    void get_remote_ip_and_port(std::string& ip, int& port) const override {
        sockaddr_storage addr{};
        socklen_t len = sizeof(addr);
        if (::getpeername(m_sock, reinterpret_cast<sockaddr*>(&addr), &len) == 0)
            address_of(addr, ip, port);
    }
    void get_local_ip_and_port(std::string& ip, int& port) const override {
        sockaddr_storage addr{};
        socklen_t len = sizeof(addr);
        if (::getsockname(m_sock, reinterpret_cast<sockaddr*>(&addr), &len) == 0)
            address_of(addr, ip, port);
    }
    socket_t socket() const override { return m_sock; }

private:
    Clock::time_point read_deadline() const {
        return m_in_body ? m_request_deadline : std::min(m_head_deadline, m_request_deadline);
    }

    /// Polls for `events` in slices until `deadline`; false at the deadline, on an error or when
    /// stopping.
    bool wait(short events, Clock::time_point deadline) const {
        while (!m_stopping()) {
            const auto left =
                std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
            if (left.count() <= 0) return false;
            pollfd p{m_sock, events, 0};
            const int r = ::poll(&p, 1, static_cast<int>(std::min(left, kWaitSlice).count()));
            if (r < 0 && errno == EINTR) continue;
            if (r < 0) return false;
            if (r > 0) return (p.revents & (events | POLLHUP | POLLERR)) != 0;
        }
        return false;
    }

    ssize_t fill() {
        ssize_t n = 0;
        do {
            n = ::recv(m_sock, m_buffer.data(), m_buffer.size(), 0);
        } while (n < 0 && errno == EINTR);
        m_begin = 0;
        m_end = n > 0 ? static_cast<std::size_t>(n) : 0;
        return n;
    }

    socket_t m_sock;
    RequestLimits m_limits;
    std::function<bool()> m_stopping;
    std::array<char, 4096> m_buffer{};
    std::size_t m_begin = 0, m_end = 0;
    Clock::time_point m_head_deadline{}, m_request_deadline{};
    std::size_t m_head_bytes = 0, m_body_bytes = 0;
    bool m_in_body = false;
    std::uint64_t m_tail = 0;
};

/// Closes after reading and discarding, for a moment, what the client is still sending.
void close_lingering(socket_t sock) {
    ::shutdown(sock, SHUT_WR);
    const auto deadline = Clock::now() + kLingerTime;
    std::array<char, 4096> discard{};
    std::size_t drained = 0;
    while (drained < kLingerBytes) {
        const auto left =
            std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
        if (left.count() <= 0) break;
        pollfd p{sock, POLLIN, 0};
        if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) break;
        const ssize_t n = ::recv(sock, discard.data(), discard.size(), 0);
        if (n <= 0) break;
        drained += static_cast<std::size_t>(n);
    }
    ::close(sock);
}
}  // namespace

GuardedServer::GuardedServer(const RequestLimits& limits) : m_limits(limits) {
    new_task_queue = [] { return new ThreadPerConnection(); };
    set_keep_alive_max_count(kKeepAliveRequests);
    // Every request's content goes through the handlers' own bounded readers; this is a backstop.
    set_payload_max_length(limits.max_body_bytes);
    // The logger runs after each answer is written, on the connection's thread.
    set_logger([](const httplib::Request&, const httplib::Response& res) {
        if (res.status >= 400) t_close_after_request = true;
    });
}

GuardedServer::~GuardedServer() = default;

void GuardedServer::set_listen_backlog(int backlog) {
    if (svr_sock_ != INVALID_SOCKET) ::listen(svr_sock_, backlog);
}

void GuardedServer::close_after_this_request() { t_close_after_request = true; }

bool GuardedServer::process_and_close_socket(socket_t sock) {
    struct Count {
        std::atomic<std::size_t>& n;
        std::size_t value;
        explicit Count(std::atomic<std::size_t>& c) : n(c), value(++c) {}
        ~Count() { --n; }
    } count(m_open);
    if (count.value > m_limits.max_connections) {
        static constexpr char kBusy[] =
            "HTTP/1.1 503 Service Unavailable\r\nContent-Length: 0\r\nConnection: "
            "close\r\nRetry-After: 1\r\n\r\n";
        [[maybe_unused]] const ssize_t ignored =
            ::send(sock, kBusy, sizeof(kBusy) - 1, MSG_NOSIGNAL | MSG_DONTWAIT);
        close_lingering(sock);
        return false;
    }
    BoundedStream stream(sock, m_limits, [this] { return svr_sock_ == INVALID_SOCKET; });
    bool ok = false;
    for (std::size_t left = kKeepAliveRequests; left > 0; --left) {
        if (!stream.wait_for_request(m_limits.idle_timeout)) break;
        stream.begin_request();
        t_close_after_request = false;
        bool connection_closed = false;
        ok = process_request(stream, left == 1, connection_closed, nullptr);
        if (!ok || connection_closed || t_close_after_request) break;
    }
    close_lingering(sock);
    return ok;
}

void ThreadPerConnection::enqueue(std::function<void()> fn) {
    {
        std::lock_guard lock(m_mutex);
        ++m_running;
    }
    std::thread([this, fn = std::move(fn)] {
        fn();
        std::lock_guard lock(m_mutex);
        if (--m_running == 0) m_done.notify_all();
    }).detach();
}

void ThreadPerConnection::shutdown() {
    std::unique_lock lock(m_mutex);
    m_done.wait(lock, [this] { return m_running == 0; });
}

}  // namespace tirpol::live::detail
