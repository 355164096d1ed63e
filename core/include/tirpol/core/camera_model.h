#pragma once
/// \file camera_model.h
/// The calibrated camera: intrinsics and lens distortion (`CameraModel`) and the camera's pose in a
/// scene's world frame (`CameraPose`), and their YAML files. core owns these files so that
/// calibration (which writes them) and simulation (which renders through them) share one reader.
///
/// Conventions (docs/camera-geometry.md): OpenCV's pinhole + Brown–Conrady model, exactly as
/// cv::projectPoints applies it. Pixel coordinates follow OpenCV: the *centre* of the top-left
/// pixel is (0, 0), u to the right along a row, v down the columns. Camera axes: x right, y down, z
/// forward (the optical axis). The files are OpenCV FileStorage YAML (cv::FileStorage reads them,
/// e.g. `fs["camera_matrix"]`, `fs["distortion_coefficients"]`), with units in the key names.

#include <filesystem>
#include <string>
#include <vector>

#include "tirpol/core/geometry.h"

namespace tirpol {

using Vec2 = Eigen::Vector2d;

/// OpenCV's distortion vector layouts, by length: 5 (k1 k2 p1 p2 k3, "standard"), 8 (+ k4 k5 k6,
/// "rational"), 12 (+ s1 s2 s3 s4, "thin_prism").
std::size_t distortion_length(const std::string& model);
/// The model name of a distortion vector of `length` coefficients; throws for other lengths.
std::string distortion_model_of_length(std::size_t length);

struct CameraModel {
    int width = 0, height = 0;  ///< image size, pixels
    double fx = 0.0, fy = 0.0, cx = 0.0,
           cy = 0.0;  ///< pixels; (cx, cy) in OpenCV's centre-origin convention
    std::vector<double> distortion =
        std::vector<double>(5, 0.0);  ///< OpenCV order k1 k2 p1 p2 k3 [k4 k5 k6 [s1..s4]]

    // What the calibration measured (zero / empty when the model was written by hand).
    double rms_px = 0.0;  ///< total RMS reprojection error
    int views = 0;        ///< views used
    std::vector<double>
        std_dev;         ///< 1σ of fx fy cx cy then the distortion coefficients, same order
    std::string target;  ///< target description, e.g. "checkerboard:9x6:0.04"

    std::string distortion_model() const { return distortion_model_of_length(distortion.size()); }
    /// Projects a point given in camera coordinates (metres, z forward) to OpenCV pixel
    /// coordinates, applying the distortion as cv::projectPoints does. The point must have z > 0.
    Vec2 project(const Vec3& point_camera) const;
    /// Normalised undistorted image coordinates (x/z, y/z) of OpenCV pixel (u, v): the exact
    /// inverse of project() (fixed-point start, then Newton on the forward model to 1e-12).
    /// Inline for a distortion-free lens, where it is affine: the renderer calls it per camera ray.
    Vec2 undistort(const Vec2& pixel) const {
        const Vec2 goal((pixel.x() - cx) / fx, (pixel.y() - cy) / fy);
        for (double c : distortion)
            if (c != 0.0) return undistort_distorted(goal);
        return goal;
    }

private:
    /// undistort() of a lens with distortion, from the distortion-free coordinates `goal`.
    Vec2 undistort_distorted(const Vec2& goal) const;
};

/// Where the camera is: x_camera = R · x_world + t (OpenCV's rvec/tvec convention, R as a matrix).
struct CameraPose {
    Mat3 camera_from_world = Mat3::Identity();  ///< R
    Vec3 translation_m = Vec3::Zero();          ///< t
    // What the pose estimate measured (zero when written by hand).
    double rms_px = 0.0;
    int points = 0;                          ///< control points used (RANSAC inliers)
    Vec3 rotation_sigma_deg = Vec3::Zero();  ///< 1σ of the rotation about the camera's x, y, z axes
    Vec3 position_sigma_m = Vec3::Zero();    ///< 1σ of the camera position in world x, y, z

    /// The camera centre in world coordinates, −Rᵀt.
    Vec3 position_m() const { return -camera_from_world.transpose() * translation_m; }
};

/// Reads a camera model YAML (docs/camera-geometry.md). Errors name the file and the field.
CameraModel read_camera_model(const std::filesystem::path& path);
/// Writes it atomically, readable by cv::FileStorage and read_camera_model.
void write_camera_model(const std::filesystem::path& path, const CameraModel& model);

CameraPose read_camera_pose(const std::filesystem::path& path);
void write_camera_pose(const std::filesystem::path& path, const CameraPose& pose);

/// Checks a model's values (positive size and focal lengths, a known distortion length); throws
/// naming `where` and the field.
void validate_camera_model(const CameraModel& model, const std::string& where);

}  // namespace tirpol
