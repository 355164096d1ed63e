// tirpol.acquisition: cameras opened by URI (aravis://, v4l2://, sim://), frames as numpy arrays.
// Device failures raise tirpol.DeviceError (device_errors.h); grabs wait with the GIL released.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <chrono>
#include <cmath>
#include <functional>

#include "bindings.h"
#include "device_errors.h"
#include "image_conversion.h"
#include "interruptible.h"
#include "tirpol/acquisition/camera.h"
#include "tirpol/acquisition/capture_plan.h"
#include "tirpol/acquisition/stage.h"
#include "tirpol/twin/scene_camera.h"

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

/// A timeout argument as milliseconds: finite and in [0, max_s] (the capture plan's limits), else
/// ValueError naming the argument as Python spells it. A NaN or 1e300 would otherwise become a
/// nonsense (or undefined) integer count of milliseconds.
std::chrono::milliseconds milliseconds(double seconds, const char* argument, double max_s) {
    if (!(seconds >= 0.0 && seconds <= max_s))
        throw py::value_error(
            fmt::format("{}: expected a finite number of seconds in [0, {}], got {}", argument,
                        max_s, seconds));
    return std::chrono::milliseconds(static_cast<long>(seconds * 1000.0));
}

/// A stage motion that Ctrl-C stops: the signal makes the calling thread send Stage::stop(), so the
/// motion ends (DeviceErrorCode::Stopped) with the stage standing where it stopped.
void interruptible_motion(acquisition::Stage& stage,
                          const std::function<acquisition::Status()>& motion) {
    check(run_interruptible([&](const std::atomic<bool>&) { return motion(); },
                            [&] { stage.stop(); }));
}

void bind_stage(py::module_& m) {
    using acquisition::Stage;
    py::class_<Stage, std::unique_ptr<Stage>>(
        m, "Stage", "A rotation stage opened by URI (docs/acquisition-stages.md).")
        .def_property_readonly("info",
                               [](const Stage& s) {
                                   const auto i = s.info();
                                   py::dict d;
                                   d["uri"] = i.uri;
                                   d["vendor"] = i.vendor;
                                   d["model"] = i.model;
                                   d["serial"] = i.serial;
                                   d["firmware"] = i.firmware;
                                   d["counts_per_degree"] = i.counts_per_degree;
                                   return d;
                               })
        .def(
            "home",
            [](Stage& s, double timeout_s) {
                const auto timeout =
                    milliseconds(timeout_s, "timeout_s", acquisition::kMaxMoveTimeoutSeconds);
                interruptible_motion(s, [&] { return s.home(timeout); });
            },
            py::arg("timeout_s") = 60.0,
            "Homes the stage; Ctrl-C stops it (KeyboardInterrupt, stage stopped).")
        .def_property_readonly("is_homed", &Stage::is_homed)
        .def(
            "move_absolute",
            [](Stage& s, double angle_deg, double timeout_s) {
                if (!std::isfinite(angle_deg))
                    throw py::value_error(fmt::format(
                        "angle_deg: expected a finite angle in degrees, got {}", angle_deg));
                const auto timeout =
                    milliseconds(timeout_s, "timeout_s", acquisition::kMaxMoveTimeoutSeconds);
                interruptible_motion(s, [&] { return s.move_absolute(angle_deg, timeout); });
            },
            py::arg("angle_deg"), py::arg("timeout_s") = 60.0,
            "Moves to angle_deg and waits until the move is done; Ctrl-C stops the stage "
            "(KeyboardInterrupt).")
        .def(
            "position_deg",
            [](Stage& s) {
                py::gil_scoped_release release;
                return value_or_raise(s.position_deg());
            },
            "The angle read back from the device, degrees.")
        .def(
            "stop", [](Stage& s) { check(s.stop()); }, "Stops any motion now.");
    m.def(
        "open_stage",
        [](const std::string& uri) {
            py::gil_scoped_release release;
            return value_or_raise(acquisition::open_stage(uri));
        },
        py::arg("uri"),
        "Opens a rotation stage: thorlabs-apt:///dev/ttyUSB0, elliptec:///dev/ttyUSB0, "
        "sim://?deg_per_s=&start_deg= "
        "(docs/acquisition-stages.md). Device failures raise tirpol.DeviceError.");
}

}  // namespace

void bind_acquisition(py::module_& m) {
    // The renderer-backed sim://<scene.yaml> camera, as the CLI registers it at start-up:
    // open_camera takes it once the package is imported.
    twin::register_twin_device_schemes();
    bind_stage(m);
    bind_capture(m);
    py::class_<Camera, std::unique_ptr<Camera>>(
        m, "Camera",
        "A camera opened by URI (docs/acquisition-cameras.md). Use it as a "
        "context manager to stop streaming on exit.")
        .def_property_readonly("info", [](const Camera& c) { return info_dict(c.info()); })
        .def(
            "set_pixel_format",
            [](Camera& c, const std::string& f) { check(c.set_pixel_format(f)); },
            py::arg("format"))
        .def(
            "set_frame_rate", [](Camera& c, double hz) { check(c.set_frame_rate(hz)); },
            py::arg("hz"))
        .def(
            "start", [](Camera& c) { check(c.start()); }, "Starts streaming.")
        .def(
            "stop", [](Camera& c) { check(c.stop()); }, "Stops streaming.")
        .def(
            "grab",
            [](Camera& c, double timeout_s) {
                const auto timeout =
                    milliseconds(timeout_s, "timeout_s", acquisition::kMaxFrameTimeoutSeconds);
                acquisition::Result<acquisition::Frame> frame = [&] {
                    py::gil_scoped_release release;
                    return c.grab(timeout);
                }();
                return frame_dict(value_or_raise(std::move(frame)));
            },
            py::arg("timeout_s") = 2.0,
            "The next complete frame: {'counts': float32 (H, W), 'frame_id' (monotonic), "
            "'device_timestamp_ns', "
            "'host_timestamp_ns', 'fpa_temperature_k'}. Raises tirpol.DeviceError (code 'timeout', "
            "...) otherwise.")
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
        "Opens a camera: aravis://<device-id>[?pixel_format=&width=&height=&fps=], "
        "v4l2:///dev/videoN, "
        "sim://uniform?width=&height=&counts=&noise=&fps=, or "
        "sim://<scene.yaml>[?width=&height=&spp=&fps=] (the "
        "scene rendered once, seen through the digital twin's wire grid and detector). A malformed "
        "URI raises "
        "tirpol.Error, an absent or refusing device tirpol.DeviceError.");
    m.def(
        "list_cameras",
        [] {
            std::vector<acquisition::CameraDescriptor> cameras;
            {
                py::gil_scoped_release release;
                cameras = acquisition::list_cameras();
            }
            py::list out;
            for (const auto& c : cameras)
                out.append(
                    py::dict(py::arg("uri") = c.uri, py::arg("description") = c.description));
            return out;
        },
        "Cameras reachable now: Aravis discovery (GigE Vision, USB3 Vision; takes about 1 s) and "
        "the V4L2 capture "
        "devices among /dev/video*, as a list of {'uri': pass to open_camera, 'description': "
        "vendor, model, "
        "address or driver}. Releases the GIL.");
}

}  // namespace tirpol::python
