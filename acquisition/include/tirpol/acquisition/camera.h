#pragma once
/// \file camera.h
/// The camera interface. Back ends: Aravis (GenICam: GigE Vision / USB3 Vision), V4L2 (UVC thermal
/// cores), simulated (frame generator). Opened by URI: `aravis://<device-id>`,
/// `v4l2:///dev/videoN`, `sim://<name>`, or any scheme added with register_camera_scheme:
///   aravis://<device-id>[?pixel_format=Mono14&width=W&height=H&fps=F&trigger=software&buffers=N&packet_size=auto|keep&microgrid=90,45,135,0]
///   v4l2:///dev/videoN[?format=Y16|GREY&width=W&height=H&fps=F&buffers=N&microgrid=90,45,135,0]
///   sim://uniform?width=W&height=H&counts=C&noise=N&fps=F[&bits=B&drop=P&seed=S&fpa_k=T]
/// (the digital twin adds the renderer-backed sim://<scene.yaml>:
/// tirpol::twin::register_twin_device_schemes).
///
/// `tirpol devices`: the cameras that can be opened now and the serial ports where a rotation
/// stage may be, with the list's JSON and text formats.

#include <array>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tirpol/acquisition/result.h"

namespace tirpol::acquisition {

/// What a camera core wrote into the frame itself (a FLIR Lepton's telemetry rows, which the
/// camera splits off the image): its own frame counter and flat-field-correction (FFC) state.
struct FrameTelemetry {
    std::uint32_t device_frame_counter = 0;  ///< the core's frame counter (not the host's id)
    /// 0 never commanded, 1 imminent, 2 in progress (shutter closed), 3 complete.
    int ffc_state = 0;
    std::uint32_t uptime_ms = 0;              ///< the core's time since power-up
    std::uint32_t uptime_at_last_ffc_ms = 0;  ///< changes whenever the core has run an FFC
};

/// One frame as delivered by a camera: raw counts converted to float (exact for ≤ 24-bit data).
struct Frame {
    int width = 0, height = 0;
    std::vector<float> counts;   ///< row-major, origin top-left
    std::uint64_t frame_id = 0;  ///< the device's id, unwrapped to a monotonic 64-bit count
    std::int64_t device_timestamp_ns = 0;  ///< the device's timestamp (0 if none)
    std::int64_t host_timestamp_ns = 0;    ///< host CLOCK_REALTIME at reception
    std::optional<double>
        fpa_temperature_k;  ///< sensor/device temperature when the camera exposes one
    std::optional<FrameTelemetry> telemetry;  ///< when the frame carried the core's telemetry
};

struct CameraInfo {
    std::string uri;  ///< how to open it again
    std::string vendor, model, serial;
    std::string pixel_format;  ///< "Mono16", "Mono14", "Y16", "PolarizeMono12", ...
    int width = 0, height = 0;
    int bits_per_pixel = 0;
    std::optional<double> frame_rate_hz;
    std::map<std::string, double>
        planck_constants;  ///< FLIR-style R, B, F, O (R1, R2, ...) when present
    /// A microgrid (division-of-focal-plane) camera's analyzer angles, degrees, at cell positions
    /// (0,0), (0,1), (1,0), (1,1) of (y mod 2, x mod 2): the sensor's layout for a polarized pixel
    /// format, or the pattern declared in the URI (`microgrid=`) for a plain monochrome one; absent
    /// for a camera without a microgrid.
    std::optional<std::array<double, 4>> microgrid_pattern_deg;
};

/// Parses a declared microgrid pattern: "sony" (the Sony IMX250MZR layout 90,45,135,0) or four
/// comma-separated angles in degrees, each finite, in [0, 180) and distinct. Throws tirpol::Error
/// naming `context` and the text otherwise. (Whether the four determine S1 and S2 is checked where
/// frames are reduced: calibration's MicrogridPattern.)
std::array<double, 4> parse_microgrid_pattern_deg(std::string_view text, std::string_view context);

struct StreamStatistics {
    std::uint64_t delivered = 0;   ///< complete frames handed out
    std::uint64_t dropped = 0;     ///< frames lost (gaps in frame ids)
    std::uint64_t incomplete = 0;  ///< frames that arrived damaged and were discarded
};

class Camera {
public:
    virtual ~Camera() = default;
    virtual CameraInfo info() const = 0;
    virtual Status set_pixel_format(const std::string& format) = 0;
    virtual Status set_frame_rate(double hz) = 0;
    virtual Status start() = 0;
    virtual Status stop() = 0;
    /// Next complete frame, waiting at most `timeout`.
    virtual Result<Frame> grab(std::chrono::milliseconds timeout) = 0;
    virtual StreamStatistics statistics() const = 0;
    /// Device temperature now, if the camera exposes one.
    virtual std::optional<double> device_temperature_k() { return std::nullopt; }
};

// Opening cameras by URI and listing those present.

/// Opens the camera a URI names, through the factory registered for its scheme. A malformed URI
/// (unknown scheme — the message lists the registered ones —, unknown query key, a value that does
/// not parse) throws tirpol::Error naming it; a device that is absent or refuses the settings is a
/// DeviceError.
Result<std::unique_ptr<Camera>> open_camera(const std::string& uri);

/// Makes the camera of a URI of its scheme (the whole URI is passed; parse it with device_uri.h).
using CameraFactory = std::function<Result<std::unique_ptr<Camera>>(const std::string& uri)>;

/// Adds the factory for `scheme` (the part before "://"), or replaces the one registered, and
/// returns the replaced factory (empty if there was none) so that a plug-in can take part of a
/// scheme and pass the other URIs on. The built-in schemes (aravis and v4l2 when built with them,
/// sim) are registered this way on first use of the registry. Thread-safe.
CameraFactory register_camera_scheme(const std::string& scheme, CameraFactory factory);

/// The registered camera schemes, sorted.
std::vector<std::string> camera_schemes();

struct CameraDescriptor {
    std::string uri;          ///< pass to open_camera
    std::string description;  ///< vendor, model, address or driver
};

/// Cameras reachable now: Aravis discovery (GigE Vision, USB3 Vision; ~1 s) and the V4L2 capture
/// devices among /dev/video*.
std::vector<CameraDescriptor> list_cameras();

/// A serial port a stage may be on.
struct SerialPort {
    std::string path;    ///< the stable name when there is one (/dev/serial/by-id/…)
    std::string device;  ///< the kernel node it points to (/dev/ttyUSB0)
};

/// Under `dev` (normally /dev): serial/by-id/* first (names carry vendor and serial, stable across
/// re-plugging), then the ttyUSB* (FTDI, as in Thorlabs K-Cube/T-Cube and Elliptec bus boards) and
/// ttyACM* nodes that no by-id link already names, each group sorted by name.
std::vector<SerialPort> list_serial_ports(const std::filesystem::path& dev = "/dev");

/// The cameras (list_cameras) and serial ports found now.
struct DeviceList {
    std::vector<CameraDescriptor> cameras;
    std::vector<SerialPort> serial_ports;
};

/// Discovers cameras and serial ports (about a second: Aravis discovery).
DeviceList list_devices();

/// {"cameras": [{uri, description}], "serial_ports": [{path, device}]}.
nlohmann::json device_list_json(const DeviceList& devices);

/// The two lists as text, with the stage URI schemes a port is used in and a note when a list is
/// empty.
std::string device_list_text(const DeviceList& devices);

}  // namespace tirpol::acquisition
