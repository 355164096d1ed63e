#pragma once
// A LiveView and its LiveServer serving on their own thread for the duration of a test, and raw
// HTTP over a loopback socket for the tests that must control every byte a client sends.

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <string>
#include <thread>

#include "httplib_after_eigen.h"
#include "live_view.h"
#include "tirpol/live/live_server.h"

namespace tirpol::test {

inline constexpr const char* kLiveTestCamera =
    "sim://uniform?width=32&height=24&counts=1500&noise=2&fps=50&fpa_k=300";

inline live::LiveViewOptions live_test_options(const std::string& stage_uri = "") {
    live::LiveViewOptions o;
    o.camera_uri = kLiveTestCamera;
    o.stage_uri = stage_uri;
    o.cycle.settle_s = 0.02;
    o.cycle.frames_per_angle = 1;
    return o;
}

struct ServedLiveView {
    live::LiveView view;
    live::LiveServer server;
    std::thread thread;
    explicit ServedLiveView(const std::string& bind,
                            live::LiveViewOptions options = live_test_options(),
                            live::RequestLimits limits = {})
        : view(options), server(view, {bind, 0, limits}) {
        thread = std::thread([this] { server.run(); });
        for (int i = 0; i < 200;
             ++i) {  // listen_after_bind starts accepting at once; give it a moment
            httplib::Client probe("127.0.0.1", server.port());
            if (auto r = probe.Get("/live.css"); r && r->status != 503) break;
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
    }
    ~ServedLiveView() {
        server.stop();
        thread.join();
    }
    std::string host() const { return "127.0.0.1:" + std::to_string(server.port()); }
    std::string origin() const { return "http://" + host(); }
};

/// A client socket to 127.0.0.1:port (closed with the object).
class RawConnection {
public:
    explicit RawConnection(int port) {
        m_fd = ::socket(AF_INET, SOCK_STREAM, 0);
        sockaddr_in addr{};
        addr.sin_family = AF_INET;
        addr.sin_port = htons(static_cast<std::uint16_t>(port));
        addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        m_connected = ::connect(m_fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) == 0;
    }
    ~RawConnection() {
        if (m_fd >= 0) ::close(m_fd);
    }
    RawConnection(const RawConnection&) = delete;
    RawConnection& operator=(const RawConnection&) = delete;

    bool connected() const { return m_connected; }
    /// Sends all of `bytes`; false if the server closed or reset the connection first.
    bool send(const std::string& bytes) {
        std::size_t sent = 0;
        while (sent < bytes.size()) {
            const ssize_t n = ::send(m_fd, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
            if (n <= 0) return false;
            sent += static_cast<std::size_t>(n);
        }
        return true;
    }
    /// What the server sends until it closes the connection, a complete response with a
    /// Content-Length arrived, or `timeout` passed.
    std::string receive(std::chrono::milliseconds timeout) {
        std::string out;
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        while (true) {
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                deadline - std::chrono::steady_clock::now());
            if (left.count() <= 0) break;
            pollfd p{m_fd, POLLIN, 0};
            if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) break;
            char buf[4096];
            const ssize_t n = ::recv(m_fd, buf, sizeof(buf), 0);
            if (n <= 0) {
                m_closed = true;
                break;
            }
            out.append(buf, static_cast<std::size_t>(n));
            if (complete(out)) break;
        }
        return out;
    }
    /// Whether receive() saw the server close the connection.
    bool closed_by_server() const { return m_closed; }

    /// The status code of a response text ("HTTP/1.1 413 …" → 413), 0 if none.
    static int status_of(const std::string& response) {
        if (response.rfind("HTTP/1.1 ", 0) != 0 || response.size() < 12) return 0;
        return std::stoi(response.substr(9, 3));
    }
    static std::string body_of(const std::string& response) {
        const auto at = response.find("\r\n\r\n");
        return at == std::string::npos ? "" : response.substr(at + 4);
    }

private:
    static bool complete(const std::string& text) {
        const auto at = text.find("\r\n\r\n");
        if (at == std::string::npos) return false;
        const std::string head = text.substr(0, at);
        for (const char* name : {"Content-Length: ", "content-length: "}) {
            const auto p = head.find(name);
            if (p != std::string::npos)
                return text.size() - at - 4 >=
                       std::stoull(head.substr(p + std::string(name).size()));
        }
        return false;
    }
    int m_fd = -1;
    bool m_connected = false;
    bool m_closed = false;
};

/// One request over a fresh connection: its response text.
inline std::string raw_request(
    int port, const std::string& request,
    std::chrono::milliseconds timeout = std::chrono::milliseconds(5000)) {
    RawConnection c(port);
    if (!c.connected() || !c.send(request)) return "";
    return c.receive(timeout);
}

}  // namespace tirpol::test
