#pragma once
/// \file capture.h
/// The capture loop: for each plan step not yet in the session — move the stage, settle, read the
/// angle back and check it, discard every frame exposed before the settle end (FrameGate: a
/// free-running camera's queue holds frames from the move), keep the next N, read the angle back
/// again (a stage that moved during the frames fails the step), average the frames (mean and
/// standard deviation per pixel), and hand the record to a writer thread so that EXR writing never
/// stalls grabbing. Software trigger is not needed. Device failures become tirpol::Error naming the
/// step; everything recorded before stays, and running again on the resumed session continues with
/// the first missing step.

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "tirpol/acquisition/blackbody.h"
#include "tirpol/acquisition/camera.h"
#include "tirpol/acquisition/capture_plan.h"
#include "tirpol/acquisition/ffc.h"
#include "tirpol/acquisition/stage.h"
#include "tirpol/core/session.h"

namespace tirpol::acquisition {

/// Where a capture stands, for CaptureOptions::on_progress.
struct CaptureProgress {
    enum class Event {
        Frame,         ///< a frame was kept for the current step (exposed after its settle end)
        StepRecorded,  ///< the step's averaged record was handed to the session writer
    };
    Event event = Event::Frame;
    /// The current step (index, kind, label, angle_deg, file); never null, valid during the call.
    const CaptureStep* step = nullptr;
    std::size_t steps_total = 0;  ///< steps in the plan
    std::size_t steps_recorded =
        0;  ///< steps in the session, earlier runs included (this one counted once recorded)
    int frames_kept = 0;         ///< frames of the current step averaged so far (of step->frames)
    std::uint64_t frame_id = 0;  ///< Frame: the id of the frame just kept
};

struct CaptureOptions {
    /// Called before each reference step with an instruction for the operator ("Put the blackbody
    /// at 313.15 K in front of the camera"); return false to stop. Empty = non-interactive.
    std::function<bool(const std::string& instruction)> prompt;
    /// Progress bar stream (nullptr: none).
    std::FILE* progress_stream = stderr;
    /// Set (e.g. by a SIGINT handler) to stop after the current frame; the session stays resumable.
    const std::atomic<bool>* interrupt = nullptr;
    /// Sets the temperatures of the plan's controlled blackbody references (required when the plan
    /// has any: capture_plan.h `controller`); each such step first waits for the set-point
    /// (blackbody_wait.h), polls the controller during its frames and records the readings.
    BlackbodyController* blackbody = nullptr;
    /// Called on the capturing thread after each kept frame and after each recorded step (a
    /// notebook's progress bar). An exception it throws ends the capture like a device error: the
    /// steps recorded before stay and the session resumes. Empty: not called.
    std::function<void(const CaptureProgress&)> on_progress;
    /// Flat-field corrections (ffc.h): set, the polarizer steps of each plan repeat are one cycle
    /// whose records are written only once the cycle is free of FFCs; FFCs are scheduled between
    /// cycles through `ffc->control` when given, and a cycle an FFC fell in is taken again. Null:
    /// frames are not watched for FFCs (a core left in auto FFC can bias S1 and S2).
    const FfcOptions* ffc = nullptr;
};

struct CaptureSummary {
    std::size_t steps_total = 0;
    std::size_t steps_already_recorded = 0;  ///< found in the session when the run started
    std::size_t steps_recorded = 0;          ///< recorded by this run
    std::uint64_t frames = 0, dropped = 0;   ///< by this run
    std::uint64_t stale_discarded =
        0;  ///< frames exposed before their step's settle end, by this run
    std::optional<double> delivered_frame_rate_hz;  ///< measured from the frames' reception times
    int ffc_scheduled = 0;  ///< FFCs run between cycles by this run (CaptureOptions::ffc)
    int ffc_detected = 0;   ///< FFCs found inside a cycle, each followed by taking that cycle again
    int home_checks = 0;    ///< passing lost-step checks at the home sensor (plan home_check_every)
};

/// Bytes a session of `steps` records of width × height frames may need (EXR upper bound).
std::uintmax_t session_bytes_needed(int width, int height, std::size_t steps);
/// Throws tirpol::Error saying how much is needed and how much is free when `dir`'s file system
/// cannot hold `steps` more records.
void check_free_space(const std::filesystem::path& dir, int width, int height, std::size_t steps);

/// The manifest of a new session for these devices and this plan (records empty; the camera's
/// frame_rate_hz null until run_capture measures the delivered rate).
SessionManifest new_session_manifest(const CameraInfo& camera, const StageInfo& stage,
                                     const CapturePlan& plan,
                                     const BlackbodyInfo* blackbody = nullptr);

/// Checks that a session being resumed was started with this plan and an identical camera format;
/// throws tirpol::Error naming what differs.
void check_resumable(const SessionManifest& manifest, const CameraInfo& camera,
                     const CapturePlan& plan);

/// Puts a simulated camera (`sim://`, the twin's `sim://<scene.yaml>`) behind the polarizer that
/// `stage` turns, so that each frame shows the scene through the polarizer where the stage has it
/// when the frame is exposed: an in-process `sim://` stage gives its time-true angle (also
/// mid-move); a driver stage (Thorlabs APT, Elliptec — e.g. tirpol-stage-sim on a pseudo-terminal)
/// the last angle its driver moved to or read back (frames taken during a move show the previous
/// angle; the capture's frame gate discards those anyway). A camera that is not simulated, or one
/// given an angle source of its own, is left alone. Returns the stage to use from now on (`stage`
/// itself, or a wrapper that forwards every call to it); the coupling ends when that stage is
/// destroyed.
std::unique_ptr<Stage> couple_simulated_polarizer(Camera& camera, std::unique_ptr<Stage> stage);

/// Runs every step of `plan` that `session` does not have yet, then marks the session complete.
CaptureSummary run_capture(Camera& camera, Stage& stage, const CapturePlan& plan,
                           SessionWriter& session, const CaptureOptions& options = {});

}  // namespace tirpol::acquisition
