#pragma once
/// \file live_options.h
/// What `tirpol live` is asked to do: which devices to open and what to show (LiveViewOptions), and
/// where and how the HTTP server listens (ServerOptions). Checked by `validate` before anything is
/// opened, so the CLI reports a bad option as a usage error.

#include <chrono>
#include <cstddef>
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

}  // namespace tirpol::live
