// tirpol.acquisition.run_capture: a capture plan run from Python into a session directory, with a
// progress callback and Ctrl-C stopping the capture after the current frame (session resumable).
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <filesystem>
#include <optional>

#include "bindings.h"
#include "interruptible.h"
#include "python_config.h"
#include "tirpol/acquisition/capture.h"

namespace py = pybind11;

namespace tirpol::python {

namespace {

using namespace tirpol::acquisition;

/// How long a device may take to return after Ctrl-C before a warning says which one hangs.
constexpr std::chrono::seconds kInterruptGrace{10};

CapturePlan plan_from_python(const py::handle& plan) {
    if (py::isinstance<py::dict>(plan))
        return CapturePlan::parse(config_from_python(plan, "<dict plan>"));
    return CapturePlan::load(plan.cast<std::filesystem::path>());
}

py::dict progress_dict(const CaptureProgress& p) {
    py::dict d;
    d["event"] = p.event == CaptureProgress::Event::Frame ? "frame" : "step";
    d["step"] = p.step->index;
    d["steps_total"] = p.steps_total;
    d["steps_recorded"] = p.steps_recorded;
    d["label"] = p.step->label;
    d["kind"] = to_string(p.step->kind);
    d["angle_deg"] = p.step->angle_deg;
    d["frames_kept"] = p.frames_kept;
    if (p.event == CaptureProgress::Event::Frame) d["frame_id"] = p.frame_id;
    d["frames"] = p.step->frames;
    d["file"] = p.step->file;
    return d;
}

py::dict summary_dict(const CaptureSummary& s) {
    py::dict d;
    d["steps_total"] = s.steps_total;
    d["steps_already_recorded"] = s.steps_already_recorded;
    d["steps_recorded"] = s.steps_recorded;
    d["frames"] = s.frames;
    d["dropped"] = s.dropped;
    d["stale_discarded"] = s.stale_discarded;
    d["delivered_frame_rate_hz"] = s.delivered_frame_rate_hz;
    return d;
}

py::dict run_capture_from_python(const py::handle& plan_source, Camera& camera, Stage& stage,
                                 const std::filesystem::path& session_dir,
                                 const py::object& progress, const py::object& prompt,
                                 bool resume) {
    const CapturePlan plan = plan_from_python(plan_source);
    CaptureOptions options;
    options.progress_stream = nullptr;
    // The callbacks run on the capturing thread: they take the GIL, and a Python exception they
    // raise (error_already_set) ends the capture and reaches the caller unchanged.
    if (!progress.is_none())
        options.on_progress = [&](const CaptureProgress& p) {
            py::gil_scoped_acquire gil;
            progress(progress_dict(p));
        };
    if (!prompt.is_none())
        options.prompt = [&](const std::string& instruction) {
            py::gil_scoped_acquire gil;
            return py::bool_(prompt(instruction)).cast<bool>();
        };
    try {
        const CaptureSummary summary = run_interruptible([&](const std::atomic<bool>& cancel) {
            // Ctrl-C: the loop stops after the current frame; a stage mid-move or mid-homing is
            // told to stop.
            StopOnInterrupt stop_stage(cancel, kInterruptGrace, [] {
                spdlog::warn("run_capture: a device has not returned {} s after the interrupt",
                             kInterruptGrace.count());
            });
            stop_stage.watch(&stage);
            options.interrupt = &cancel;
            SessionWriter session =
                open_capture_session(session_dir, camera.info(), stage.info(), plan, resume);
            return run_capture(camera, stage, plan, session, options);
        });
        return summary_dict(summary);
    } catch (...) {
        // run_capture stops the camera when it completes; a capture that ended early leaves it
        // streaming.
        py::gil_scoped_release release;
        if (auto s = camera.stop(); !s) spdlog::warn("stopping the camera: {}", s.error().message);
        throw;
    }
}

}  // namespace

void bind_capture(py::module_& m) {
    m.def("run_capture", &run_capture_from_python, py::arg("plan"), py::arg("camera"),
          py::arg("stage"), py::arg("session_dir"), py::arg("progress") = py::none(),
          py::arg("prompt") = py::none(), py::arg("resume") = false,
          "Runs a capture plan (a YAML file path or a dict with the same keys, "
          "docs/acquisition-stages.md) with "
          "`camera` and `stage` into the session directory `session_dir` (new and empty; with "
          "resume=True an "
          "interrupted session, whose recorded steps are skipped), as `tirpol acquire` does. "
          "`progress(event)` is "
          "called after each kept frame ({'event': 'frame', ...}) and after each recorded step "
          "({'event': "
          "'step', ...}) with keys step, steps_total, steps_recorded, label, kind, angle_deg, "
          "frames_kept, frames, "
          "file (and frame_id for a frame); an exception it raises stops the capture (recorded "
          "steps stay) and is "
          "re-raised. `prompt(instruction)` is asked before each reference step (return False to "
          "stop); None: "
          "non-interactive. "
          "Ctrl-C stops the capture after the current frame and the stage if it moves "
          "(KeyboardInterrupt); run "
          "again with resume=True to continue. Returns a summary dict (steps_total, "
          "steps_already_recorded, "
          "steps_recorded, frames, dropped, stale_discarded, delivered_frame_rate_hz). Releases "
          "the GIL.");
}

}  // namespace tirpol::python
