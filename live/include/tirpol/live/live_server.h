#pragma once
/// \file live_server.h
/// `tirpol live`: opens the camera (and stage) named in LiveViewOptions, streams, and serves over
/// HTTP (cpp-httplib) the page compiled into the binary and the API it polls: the page, describe,
/// status, the latest S0 and Stokes images after a sequence number (long poll, 204 after 1 s),
/// region statistics, snapshots, capture start/stop and test-mode observations. docs/live.md
/// lists the routes and their JSON. Each page asks for the next frame after drawing the last, so
/// it gets frames at its own pace.

#include <memory>
#include <string>
#include <vector>

#include "tirpol/live/live_options.h"

namespace tirpol::live {

class LiveView;

class LiveServer {
public:
    /// Validates both sets of options, opens the devices and starts streaming (tirpol::Error
    /// naming the option, URI or file that failed), and binds now (tirpol::Error naming the
    /// address and port when it cannot). A token is made and required when `bind_address` is not
    /// loopback; every request passes the request policy (docs/live.md) before its body is read.
    LiveServer(const LiveViewOptions& view_options, const ServerOptions& options);
    /// Serves a view that the caller keeps alive longer than the server (the module's tests,
    /// which read the view directly; live/src/live_view.h).
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
    /// url() first, then the same for every other address of this machine a wildcard bind is
    /// reachable at (reachable_addresses): a laptop on Ethernet and Wi-Fi prints both.
    std::vector<std::string> urls() const;

    /// Serves until stop() (from another thread or a signal-watching thread).
    void run();
    void stop();
    /// Serves until Ctrl-C (SIGINT/SIGTERM; a second one ends the process at once) or stop().
    void run_until_interrupted();
    /// What `tirpol live` prints once listening: the addresses to open (urls()) and, for a
    /// non-loopback bind, the access token every request needs.
    std::string listening_text() const;
    /// Connections being served now (for tests of the connection limit).
    std::size_t open_connections() const;

private:
    LiveServer(std::unique_ptr<LiveView> owned_view, const ServerOptions& options);
    void serve(LiveView& view, const ServerOptions& options);

    struct Impl;
    std::unique_ptr<LiveView> m_owned_view;  ///< destroyed after m_impl: the server stops first
    std::unique_ptr<Impl> m_impl;
    std::string m_bind_address, m_token;
    int m_port = 0;
};

}  // namespace tirpol::live
