// tirpol.acquisition: cameras opened by URI (aravis://, v4l2://, sim://), frames as numpy arrays.
// Device failures raise tirpol.DeviceError (device_errors.h); grabs wait with the GIL released.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <chrono>

#include "bindings.h"
#include "device_errors.h"
#include "image_conversion.h"
#include "tirpol/acquisition/camera_registry.h"

namespace py = pybind11;

namespace tirpol::python {

namespace {

using acquisition::Camera;

py::dict info_dict(const acquisition::CameraInfo& info) {
    py::dict d;
    d["uri"] = info.uri;
    d["vendor"] = info.vendor;
    d["model"] = info.model;
    d["serial"] = info.serial;
    d["pixel_format"] = info.pixel_format;
    d["width"] = info.width;
    d["height"] = info.height;
    d["bits_per_pixel"] = info.bits_per_pixel;
    d["frame_rate_hz"] = info.frame_rate_hz;
    d["planck_constants"] = info.planck_constants;
    return d;
}

py::dict frame_dict(acquisition::Frame&& frame) {
    py::dict d;
    d["frame_id"] = frame.frame_id;
    d["device_timestamp_ns"] = frame.device_timestamp_ns;
    d["host_timestamp_ns"] = frame.host_timestamp_ns;
    d["fpa_temperature_k"] = frame.fpa_temperature_k;
    d["counts"] = array_from_plane(std::move(frame.counts), frame.width, frame.height);
    return d;
}

void check(acquisition::Status&& status) { value_or_raise(std::move(status)); }

}  // namespace

void bind_acquisition(py::module_& m) {
    py::class_<Camera, std::unique_ptr<Camera>>(m, "Camera",
                                                "A camera opened by URI (docs/acquisition-cameras.md). Use it as a "
                                                "context manager to stop streaming on exit.")
        .def_property_readonly("info", [](const Camera& c) { return info_dict(c.info()); })
        .def(
            "set_pixel_format", [](Camera& c, const std::string& f) { check(c.set_pixel_format(f)); },
            py::arg("format"))
        .def(
            "set_frame_rate", [](Camera& c, double hz) { check(c.set_frame_rate(hz)); }, py::arg("hz"))
        .def(
            "start", [](Camera& c) { check(c.start()); }, "Starts streaming.")
        .def(
            "stop", [](Camera& c) { check(c.stop()); }, "Stops streaming.")
        .def(
            "grab",
            [](Camera& c, double timeout_s) {
                acquisition::Result<acquisition::Frame> frame = [&] {
                    py::gil_scoped_release release;
                    return c.grab(std::chrono::milliseconds(static_cast<long>(timeout_s * 1000.0)));
                }();
                return frame_dict(value_or_raise(std::move(frame)));
            },
            py::arg("timeout_s") = 2.0,
            "The next complete frame: {'counts': float32 (H, W), 'frame_id' (monotonic), 'device_timestamp_ns', "
            "'host_timestamp_ns', 'fpa_temperature_k'}. Raises tirpol.DeviceError (code 'timeout', ...) otherwise.")
        .def("statistics",
             [](const Camera& c) {
                 const auto s = c.statistics();
                 py::dict d;
                 d["delivered"] = s.delivered;
                 d["dropped"] = s.dropped;
                 d["incomplete"] = s.incomplete;
                 return d;
             })
        .def(
            "__enter__", [](Camera& c) -> Camera& { return c; }, py::return_value_policy::reference)
        .def("__exit__", [](Camera& c, const py::args&) { c.stop(); });
    m.def(
        "open_camera",
        [](const std::string& uri) {
            py::gil_scoped_release release;
            return value_or_raise(acquisition::open_camera(uri));
        },
        py::arg("uri"),
        "Opens a camera: aravis://<device-id>[?pixel_format=&width=&height=&fps=], v4l2:///dev/videoN, "
        "sim://uniform?width=&height=&counts=&noise=&fps=. A malformed URI raises tirpol.Error, an absent or "
        "refusing device tirpol.DeviceError.");
}

}  // namespace tirpol::python
