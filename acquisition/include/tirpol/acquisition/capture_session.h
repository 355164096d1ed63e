#pragma once
/// \file capture_session.h
/// Opening the session a capture plan writes into, shared by `tirpol acquire` and the live view's
/// capture button: a new session for these devices and this plan, or an interrupted one resumed
/// after checking it was started with the same plan and camera format.

#include <filesystem>

#include "tirpol/acquisition/blackbody.h"
#include "tirpol/acquisition/camera.h"
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

}  // namespace tirpol::acquisition
