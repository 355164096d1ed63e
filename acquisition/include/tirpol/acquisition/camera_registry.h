#pragma once
/// \file camera_registry.h
/// Opening cameras by URI and listing those present.
///   aravis://<device-id>[?pixel_format=Mono14&width=W&height=H&fps=F&trigger=software&buffers=N&packet_size=auto|keep]
///   v4l2:///dev/videoN[?format=Y16|GREY&width=W&height=H&fps=F&buffers=N]
///   sim://uniform?width=W&height=H&counts=C&noise=N&fps=F[&bits=B&drop=P&seed=S&fpa_k=T]
/// and any scheme a module above acquisition adds with register_camera_scheme (the digital twin adds
/// the renderer-backed sim://<scene.yaml>: tirpol::twin::register_twin_device_schemes).

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tirpol/acquisition/camera.h"

namespace tirpol::acquisition {

/// Opens the camera a URI names, through the factory registered for its scheme. A malformed URI
/// (unknown scheme — the message lists the registered ones —, unknown query key, a value that does
/// not parse) throws tirpol::Error naming it; a device that is absent or refuses the settings is a
/// DeviceError.
Result<std::unique_ptr<Camera>> open_camera(const std::string& uri);

/// Makes the camera of a URI of its scheme (the whole URI is passed; parse it with device_uri.h).
using CameraFactory = std::function<Result<std::unique_ptr<Camera>>(const std::string& uri)>;

/// Adds the factory for `scheme` (the part before "://"), or replaces the one registered, and returns
/// the replaced factory (empty if there was none) so that a plug-in can take part of a scheme and
/// pass the other URIs on. The built-in schemes (aravis and v4l2 when built with them, sim) are
/// registered this way on first use of the registry. Thread-safe.
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

}  // namespace tirpol::acquisition
