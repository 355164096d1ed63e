#pragma once
/// \file live_server.h
/// The HTTP side of `tirpol live` (cpp-httplib): serves the page compiled into the binary and the
/// API it polls (docs/live.md):
///   GET  /  /live.js  /live.css                      the page
///   GET  /api/describe                               camera, units, stage, capture defaults (JSON)
///   GET  /api/status                                 rates, drops, FPA history, stage, capture
///   (JSON) GET  /api/frame?after=SEQ                        the latest S0 newer than SEQ
///   (display_frame.h GET  /api/stokes?after=SEQ                       format; X-Sequence header),
///   else 204 after 1 s POST /api/capture/start  {plan, output, resume}  POST /api/capture/stop
///   POST /api/observations?client=ID  GET /api/observations   what a page in test mode saw
/// Each page asks for the next frame after drawing the last, so it gets frames at its own pace.

#include <memory>
#include <string>

#include "tirpol/live/live_view.h"
#include "tirpol/live/request_policy.h"

namespace tirpol::live {

struct ServerOptions {
    std::string bind_address = "127.0.0.1";
    int port = 0;  ///< 1–65535, or 0: the system picks a free port
    RequestLimits limits;
};

/// Throws tirpol::Error naming the option (`--port`, `--bind`) when a value is out of range.
void validate(const ServerOptions& options);

class LiveServer {
public:
    /// Validates the options and binds now (tirpol::Error naming the address and port when it
    /// cannot). A token is made and required when `bind_address` is not loopback (access.h); every
    /// request passes RequestPolicy (request_policy.h) before its body is read.
    LiveServer(LiveView& view, const ServerOptions& options);
    ~LiveServer();
    LiveServer(const LiveServer&) = delete;
    LiveServer& operator=(const LiveServer&) = delete;

    int port() const { return m_port; }
    /// Empty when none is required.
    const std::string& token() const { return m_token; }
    /// The address to open in a browser, with the token when one is required: for a wildcard bind
    /// (0.0.0.0) this machine's network address (reachable_address), not 0.0.0.0.
    std::string url() const;

    /// Serves until stop() (from another thread or a signal-watching thread).
    void run();
    void stop();
    /// Connections being served now (for tests of the connection limit).
    std::size_t open_connections() const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
    std::string m_bind_address, m_token;
    int m_port = 0;
};

}  // namespace tirpol::live
