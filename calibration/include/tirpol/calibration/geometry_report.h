#pragma once
/// \file geometry_report.h
/// The text `tirpol calibrate geometric` and `tirpol calibrate pose` print: what was calibrated or
/// estimated, per view or control point, and the file written.

#include <cstddef>
#include <string>
#include <vector>

#include "tirpol/calibration/calibration_target.h"
#include "tirpol/calibration/geometric_calibration.h"
#include "tirpol/calibration/pose_estimation.h"

namespace tirpol::calibration {

/// Views used of `frames` given, frames without the target, per-view RMS and tilt (outliers
/// flagged), the total RMS, each intrinsic ± 1σ and `output`.
std::string geometric_calibration_text(const GeometricCalibrationResult& result,
                                       const CalibrationTarget& target, std::size_t frames,
                                       const std::string& output);

/// Points used, RMS, position and rotation ± 1σ, each point's residual (outliers flagged) and
/// `output`.
std::string pose_estimation_text(const PoseResult& result, const std::vector<ControlPoint>& points,
                                 const std::string& output);

}  // namespace tirpol::calibration
