#pragma once
/// \file camera_registry.h
/// Opening cameras by URI and listing those present.
///   aravis://<device-id>[?pixel_format=Mono14&width=W&height=H&fps=F&trigger=software&buffers=N&packet_size=auto|keep]
///   v4l2:///dev/videoN[?format=Y16|GREY&width=W&height=H&fps=F&buffers=N]
///   sim://uniform?width=W&height=H&counts=C&noise=N&fps=F[&bits=B&drop=P&seed=S&fpa_k=T]

#include <memory>
#include <string>
#include <vector>

#include "tirpol/acquisition/camera.h"

namespace tirpol::acquisition {

/// Opens the camera a URI names. A malformed URI (unknown scheme or query key, a value that does not
/// parse) throws tirpol::Error naming it; a device that is absent or refuses the settings is a DeviceError.
Result<std::unique_ptr<Camera>> open_camera(const std::string& uri);

struct CameraDescriptor {
    std::string uri;          ///< pass to open_camera
    std::string description;  ///< vendor, model, address or driver
};

/// Cameras reachable now: Aravis discovery (GigE Vision, USB3 Vision; ~1 s) and the V4L2 capture
/// devices among /dev/video*.
std::vector<CameraDescriptor> list_cameras();

}  // namespace tirpol::acquisition
