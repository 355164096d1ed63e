#pragma once
/// \file capture.h
/// The capture loop: for each plan step not yet in the session — move the stage, settle, read the
/// angle back and check it, grab N frames, average them (mean and standard deviation per pixel),
/// write the record. Device failures become tirpol::Error naming the step; everything recorded
/// before stays, and running again on the resumed session continues with the first missing step.

#include <atomic>
#include <cstdio>
#include <functional>
#include <string>

#include "tirpol/acquisition/camera.h"
#include "tirpol/acquisition/capture_plan.h"
#include "tirpol/acquisition/stage.h"
#include "tirpol/core/session.h"

namespace tirpol::acquisition {

struct CaptureOptions {
    /// Called before each reference step with an instruction for the operator ("Put the blackbody
    /// at 313.15 K in front of the camera"); return false to stop. Empty = non-interactive.
    std::function<bool(const std::string& instruction)> prompt;
    /// Progress bar stream (nullptr: none).
    std::FILE* progress_stream = stderr;
    /// Set (e.g. by a SIGINT handler) to stop after the current frame; the session stays resumable.
    const std::atomic<bool>* interrupt = nullptr;
};

struct CaptureSummary {
    std::size_t steps_total = 0;
    std::size_t steps_already_recorded = 0;  ///< found in the session when the run started
    std::size_t steps_recorded = 0;          ///< recorded by this run
    std::uint64_t frames = 0, dropped = 0;   ///< by this run
};

/// The manifest of a new session for these devices and this plan (records empty).
SessionManifest new_session_manifest(const CameraInfo& camera, const StageInfo& stage, const CapturePlan& plan);

/// Checks that a session being resumed was started with this plan and an identical camera format;
/// throws tirpol::Error naming what differs.
void check_resumable(const SessionManifest& manifest, const CameraInfo& camera, const CapturePlan& plan);

/// Runs every step of `plan` that `session` does not have yet, then marks the session complete.
CaptureSummary run_capture(Camera& camera, Stage& stage, const CapturePlan& plan, SessionWriter& session,
                           const CaptureOptions& options = {});

}  // namespace tirpol::acquisition
