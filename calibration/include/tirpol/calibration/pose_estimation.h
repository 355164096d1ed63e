#pragma once
/// \file pose_estimation.h
/// Camera pose from surveyed control points (world coordinates in the scene's frame and their pixel
/// positions): cv::solvePnPRansac to reject mis-picked points, then Levenberg–Marquardt refinement
/// on the inliers (cv::solvePnPRefineLM); the pose's 1σ from the reprojection Jacobian, cov =
/// σ̂²(JᵀJ)⁻¹ with σ̂² = Σr² / (2N − 6).

#include <filesystem>
#include <string>
#include <vector>

#include "tirpol/core/camera_model.h"

namespace tirpol::calibration {

struct ControlPoint {
    std::string name;
    Vec3 world_m;  ///< scene world frame (x east, y north, z up), metres
    Vec2 pixel;    ///< OpenCV pixel coordinates (centre of the top-left pixel at (0, 0))
};

/// Reads a control-point CSV with the header `name,x_m,y_m,z_m,u_px,v_px` ('#' comments allowed).
/// Errors name the file, line and column.
std::vector<ControlPoint> read_control_points(const std::filesystem::path& path);

struct PoseOptions {
    double ransac_threshold_px =
        3.0;  ///< a point further than this from its reprojection is an outlier
};

struct PoseResult {
    CameraPose pose;                  ///< with rms_px, points, rotation_sigma_deg, position_sigma_m
    std::vector<double> residual_px;  ///< per control point, input order
    std::vector<bool> inlier;         ///< per control point, input order
};

/// Estimates the pose of the camera `model` from ≥ 4 control points. Throws tirpol::Error for fewer
/// than 4 points, pixels outside the image, collinear or coincident points, too few RANSAC inliers,
/// or a solution with control points on or behind the camera (named).
PoseResult estimate_pose(const CameraModel& model, const std::vector<ControlPoint>& points,
                         const PoseOptions& options = {});

}  // namespace tirpol::calibration
