#pragma once
// An httplib::Server whose connections are bounded in number, bytes and time (RequestLimits).
// cpp-httplib 0.11 reads the request line and each header line into a buffer that grows until a
// newline arrives, keeps a connection for up to five requests of five seconds' silence each on a
// fixed pool of threads, and after answering a request without reading its body reads that body as
// the next request. So the server here replaces its per-connection loop (process_and_close_socket,
// a virtual the library provides for this) with one that reads through a BoundedStream — the
// request head capped in bytes and time, the body in bytes, the whole exchange in time — closes the
// connection after every refusal, and runs each connection on its own thread up to a connection cap
// (beyond it a connection is answered 503 and closed at once), so idle or slow connections cannot
// starve the others.

#include <atomic>
#include <condition_variable>
#include <mutex>

#include "httplib_after_eigen.h"
#include "request_policy.h"

namespace tirpol::live::detail {

class GuardedServer : public httplib::Server {
public:
    explicit GuardedServer(const RequestLimits& limits);
    ~GuardedServer() override;

    /// Sets the listening socket's accept queue to `backlog` (after binding; cpp-httplib listens
    /// with a queue of 5, so a burst of connections has the kernel drop SYNs, which clients retry
    /// only after 1 s).
    void set_listen_backlog(int backlog);
    /// Connections being served now.
    std::size_t open_connections() const { return m_open; }
    /// Marks the request being answered on this thread: its connection is closed after the answer
    /// (a refused request whose body was never read).
    static void close_after_this_request();

private:
    bool process_and_close_socket(socket_t sock) override;

    RequestLimits m_limits;
    std::atomic<std::size_t> m_open{0};
};

/// One thread per connection; shutdown() waits for every one to finish.
class ThreadPerConnection : public httplib::TaskQueue {
public:
    void enqueue(std::function<void()> fn) override;
    void shutdown() override;

private:
    std::mutex m_mutex;
    std::condition_variable m_done;
    std::size_t m_running = 0;
};

}  // namespace tirpol::live::detail
