#pragma once
/// \file capture_session.h
/// Opening the session a capture plan writes into, shared by `tirpol acquire` and the live view's
/// capture button: a new session for these devices and this plan, or an interrupted one resumed
/// after checking it was started with the same plan and camera format; and the whole of `tirpol
/// acquire` (devices by URI, the plan file, Ctrl-C) as one call.

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "tirpol/acquisition/blackbody.h"
#include "tirpol/acquisition/camera.h"
#include "tirpol/acquisition/capture.h"
#include "tirpol/acquisition/capture_plan.h"
#include "tirpol/acquisition/stage.h"
#include "tirpol/core/session.h"

namespace tirpol::acquisition {

/// `resume` false: SessionWriter::create (refuses a non-empty directory). `resume` true: the
/// directory must hold a session (tirpol::Error "no session to resume here" otherwise), which is
/// reopened with SessionWriter::resume and checked with check_resumable. `blackbody`: the
/// controller of a plan with blackbody set-points (recorded in a new session's manifest).
SessionWriter open_capture_session(const std::filesystem::path& dir, const CameraInfo& camera,
                                   const StageInfo& stage, const CapturePlan& plan, bool resume,
                                   const BlackbodyInfo* blackbody = nullptr);

/// A capture plan run by device URIs into a session directory (`tirpol acquire`).
struct AcquisitionOptions {
    std::filesystem::path plan;  ///< capture plan YAML
    std::filesystem::path session;
    std::string camera_uri, stage_uri;
    std::string blackbody_uri;       ///< empty: no controlled blackbody
    std::string camera_control_uri;  ///< empty: no FFC link (ffc_control.h)
    std::string ffc_schedule;        ///< empty: "every-cycle" with a camera control link, else none
    bool resume = false;             ///< continue the interrupted session in `session`
    /// Asked before reference frames (CaptureOptions::prompt); empty: non-interactive.
    std::function<bool(const std::string& instruction)> prompt;
};

/// What run_acquisition did.
struct AcquisitionResult {
    std::filesystem::path session;
    CaptureSummary summary;
    bool ffc = false;  ///< flat-field corrections were scheduled or watched for
    /// Files found written just before an interruption and adopted by the resumed session.
    std::vector<std::filesystem::path> recovered;
};

/// How long after Ctrl-C run_acquisition may take to leave through its clean path before the
/// process exits anyway (status 1; every session write is atomic, so nothing recorded is lost).
inline constexpr std::chrono::milliseconds kAcquisitionInterruptGrace{1000};

/// Checks the options, opens the devices and the session (new or resumed), and runs the plan.
/// While it runs, the first Ctrl-C (SIGINT/SIGTERM) stops the stage at once, also mid-move or
/// mid-homing, and ends the run after the current frame with a tirpol::Error that says how many
/// steps are recorded; a device that does not return within kAcquisitionInterruptGrace ends the
/// process. Throws tirpol::Error for a bad plan, URI or option combination and device faults.
AcquisitionResult run_acquisition(const AcquisitionOptions& options);

/// The summary `tirpol acquire` prints: steps, frames, dropped frames, flat-field corrections.
std::string acquisition_summary_text(const AcquisitionResult& result);

}  // namespace tirpol::acquisition
