#pragma once
/// \file aravis_camera.h
/// GenICam cameras (GigE Vision, USB3 Vision) through Aravis 0.8: `aravis://<device-id>`.
/// The device id is Aravis's ("<vendor>-<model>-<serial>", e.g. `Aravis-Fake-GV01`), or an IP
/// address.

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/acquisition/camera.h"

namespace tirpol::acquisition {

/// One device found by Aravis discovery (GigE Vision broadcast on every interface, USB3 Vision
/// enumeration).
struct AravisDeviceInfo {
    std::string id;  ///< pass to aravis://<id>
    std::string vendor, model, serial;
    std::string address;   ///< IP address for GigE Vision, empty for USB3 Vision
    std::string protocol;  ///< "GigEVision", "USB3Vision"
};

/// Runs Aravis discovery once (about 1 s for GigE Vision) and lists the devices found.
std::vector<AravisDeviceInfo> discover_aravis_cameras();

/// How to configure an Aravis camera when opening it (URI query: `aravis://ID?pixel_format=Mono14&
/// width=640&height=512&fps=30&trigger=software&buffers=32&packet_size=auto&microgrid=sony`).
struct AravisCameraOptions {
    /// Mono8, Mono10, Mono12, Mono14, Mono16, or a microgrid polarization sensor's raw mosaic:
    /// PolarizeMono8, PolarizeMono12, PolarizeMono12p, PolarizeMono16 (LUCID's names).
    std::optional<std::string> pixel_format;
    /// The microgrid pattern (CameraInfo::microgrid_pattern_deg): declares one for a plain
    /// monochrome format (a microgrid camera that streams Mono16), or replaces the sensor layout of
    /// a polarized format (a sensor read out mirrored).
    std::optional<std::array<double, 4>> microgrid_pattern_deg;
    std::optional<int> width, height;  ///< region of interest, from the top-left corner
    std::optional<double> frame_rate_hz;
    bool software_trigger =
        false;  ///< each grab() fires TriggerSoftware (TriggerMode=On, TriggerSource=Software)
    int stream_buffers = 32;       ///< buffers queued on the stream; more absorb host hiccups
    bool auto_packet_size = true;  ///< GigE Vision: negotiate the largest packet the path carries
    /// GigE Vision: how long to keep retrying (with a growing pause) while an earlier control
    /// session, e.g. of a program that was killed, still holds the camera until its heartbeat times
    /// out. A warning says so at the first refusal.
    std::chrono::milliseconds control_wait{15000};
};

/// Opens `device_id` and applies `options`. Errors (device absent, feature refused) as DeviceError
/// with the Aravis GError domain and code in the message. While a frame is awaited, a GigE Vision
/// camera silent for 0.5 s is probed on its control channel: one that is gone gives Disconnected
/// within about a second, not a Timeout at the end of the frame timeout.
Result<std::unique_ptr<Camera>> open_aravis_camera(const std::string& device_id,
                                                   const AravisCameraOptions& options = {});

/// Feature names probed for a frame rate, in order: a Float `AcquisitionFrameRate` (with
/// `AcquisitionFrameRateEnable` switched on when present), a Float `AcquisitionFrameRateAbs` (GigE
/// Vision SFNC 1.x), then enumerations (`AcquisitionFrameRate`, FLIR's `IRFrameRate`, `FrameRate`)
/// whose entry names carry the rate ("Rate30Hz", "Hz_7_5", "60Hz").
const std::vector<std::string>& aravis_frame_rate_feature_names();

/// Parses the rate in Hz from an enumeration entry name: digits, with '_' or 'p' as the decimal
/// point when followed by digits ("Rate7_5Hz" → 7.5, "Hz60" → 60). nullopt when there is no number.
std::optional<double> frame_rate_from_entry_name(const std::string& entry);

}  // namespace tirpol::acquisition
