#pragma once
/// \file live_server.h
/// `tirpol live`: opens the camera (and stage) named in LiveViewOptions, streams, and serves over
/// HTTP (cpp-httplib) the page compiled into the binary and the API it polls: the page, describe,
/// status, the latest S0 and Stokes images after a sequence number (long poll, 204 after 1 s),
/// region statistics, snapshots, capture start/stop and test-mode observations. docs/live.md
/// lists the routes and their JSON. Each page asks for the next frame after drawing the last, so
/// it gets frames at its own pace.
///
/// What `tirpol live` is asked to do: which devices to open and what to show (LiveViewOptions), and
/// where and how the HTTP server listens (ServerOptions). Checked by `validate` before anything is
/// opened, so the CLI reports a bad option as a usage error.

#include <chrono>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace tirpol::live {

/// What S0 shows: camera counts, or with a radiometric calibration apparent radiance or brightness
/// temperature.
enum class DisplayUnit { Counts, Radiance, Temperature };

/// Parses "counts", "radiance", "temperature"; tirpol::Error naming the value otherwise.
DisplayUnit parse_display_unit(const std::string& text);

/// The polarizer cycle with a stage: the angles it turns through and how frames are taken at each.
struct CycleOptions {
    std::vector<double> angles_deg{0.0, 45.0, 90.0, 135.0};
    int frames_per_angle = 4;
    double settle_s = 0.2;
    double move_timeout_s = 60.0;
    double home_timeout_s = 120.0;
    double frame_timeout_s = 5.0;
};

struct LiveViewOptions {
    std::string camera_uri;        ///< acquisition::open_camera
    std::string stage_uri;         ///< acquisition::open_stage; empty = no stage (S0 only)
    std::string calibration_path;  ///< radiometric calibration EXR; empty = counts only
    DisplayUnit unit = DisplayUnit::Counts;
    CycleOptions cycle;
    std::string default_plan, default_output;  ///< prefilled in the page's capture form
    /// Where the page's Snapshot button writes (empty: no snapshots). check_live_run checks it
    /// with OutputGuard before starting; `force_snapshots` lets a snapshot replace an existing
    /// file.
    std::string snapshot_dir;
    /// With a microgrid camera and no stage, the page's Stokes images come from each frame:
    /// demosaiced by this method (calibration's parse_demosaic_method: super-pixel, bilinear,
    /// newton) and reduced with ideal analyzers at the pattern's angles.
    std::string demosaic = "bilinear";
    bool force_snapshots = false;
};

/// Throws tirpol::Error naming the option (`--settle-s`, `--frames-per-angle`, …) and the value
/// when a number is not finite or out of range: NaN would otherwise pass every comparison and mean
/// "no wait".
void validate(const LiveViewOptions& options);

/// Sizes and times that bound what one client can make the server hold.
struct RequestLimits {
    std::size_t max_body_bytes = 64 * 1024;  ///< a capture request or an observation is well below
    std::size_t max_head_bytes = 16 * 1024;  ///< request line and headers together
    std::size_t max_connections = 64;        ///< open at once; one page holds a few
    std::size_t max_observation_clients =
        16;  ///< pages reporting in test mode, each ≤ max_body_bytes
    std::chrono::milliseconds idle_timeout{5000};  ///< a kept-alive connection with no request
    std::chrono::milliseconds head_timeout{
        5000};  ///< from a request's first byte to its last header
    std::chrono::milliseconds request_timeout{30000};  ///< reading and answering one request
};

struct ServerOptions {
    std::string bind_address = "127.0.0.1";
    int port = 0;  ///< 1–65535, or 0: the system picks a free port
    RequestLimits limits;
};

/// Throws tirpol::Error naming the option (`--port`, `--bind`) when a value is out of range.
void validate(const ServerOptions& options);

/// What `tirpol live` checks before it opens anything: both sets of options (`validate`; a
/// problem becomes tirpol::OptionValueError naming the option its message begins with), then the
/// snapshot folder against the inputs (OutputGuard; OutputConflict, `force_snapshots` as its
/// force), which is created.
void check_live_run(const LiveViewOptions& view, const ServerOptions& server);

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
