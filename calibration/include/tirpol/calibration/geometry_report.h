#pragma once
/// \file geometry_report.h
/// The text `tirpol calibrate geometric` and `tirpol calibrate pose` print: what was calibrated or
/// estimated, per view or control point, and the file written; and each of the two as one call
/// from files to files.

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

/// `tirpol calibrate geometric`: frames showing the target, the target as text
/// (CalibrationTarget::parse), the options and the camera model YAML to write.
struct GeometricRunOptions {
    std::vector<std::string> frames;
    std::string target, output;
    GeometricCalibrationOptions calibration;
    bool force = false;  ///< an existing output may be replaced (OutputGuard)
};

/// What run_geometric_calibration calibrated and wrote.
struct GeometricRun {
    GeometricCalibrationResult result;
    CalibrationTarget target;
    std::size_t frames = 0;
    std::string output;
};

/// Checks the output (OutputGuard) and the target text (tirpol::OptionValueError naming --target),
/// calibrates and writes the camera model.
GeometricRun run_geometric_calibration(const GeometricRunOptions& options);

/// `tirpol calibrate pose`: the camera model, the control points CSV and the pose YAML to write.
struct PoseRunOptions {
    std::string camera, points, output;
    PoseOptions pose;
    bool force = false;  ///< an existing output may be replaced (OutputGuard)
};

/// What run_pose_estimation estimated and wrote.
struct PoseRun {
    PoseResult result;
    std::vector<ControlPoint> points;
    std::string output;
};

/// Checks the output (OutputGuard), estimates the pose and writes it.
PoseRun run_pose_estimation(const PoseRunOptions& options);

}  // namespace tirpol::calibration
