#pragma once
/// \file geometric_calibration.h
/// Intrinsics and lens distortion from views of a planar target (Zhang, "A flexible new technique
/// for camera calibration", IEEE TPAMI 22(11), 2000, as implemented by cv::calibrateCamera), with
/// per-view and total RMS reprojection error, 1σ of every parameter, and outlier views flagged.
/// Pixel convention: OpenCV's (core/camera_model.h).
///
/// The text `tirpol calibrate geometric` and `tirpol calibrate pose` print: what was calibrated or
/// estimated, per view or control point, and the file written; and each of the two as one call
/// from files to files.
///
/// Finding a calibration target in a thermal frame: 14-bit counts, low contrast, blur, hot-on-cold
/// or cold-on-hot. The frame is contrast-stretched robustly (0.5th–99.5th percentile → 0–255, NaN
/// pixels filled with the frame's median) before OpenCV's detectors. Checkerboards: OpenCV's
/// sector-based detector at full resolution with its own sub-pixel refinement (CALIB_CB_ACCURACY),
/// either polarity; when that fails, again after removing stuck pixels, column offsets and the
/// large-scale background (vignetting, gradients), then with the exhaustive search. Squares under
/// 16 px (a 160×120 core's view) are refined further by cv::cornerSubPix.
/// Circle grids: both polarities are tried; centres are cv::findCirclesGrid's blob centroids.
/// docs/camera-geometry.md has the measurements behind each choice.
///
/// The planar targets of geometric calibration (docs/camera-geometry.md): a checkerboard (aluminium
/// tape on black paint, or a heated board) or a grid of circles (heated discs, holes in a cold
/// plate). Feature points lie in the target's plane z = 0 of its own frame, x along a row, y down
/// the columns, in OpenCV's detection order (row by row).
///
/// Camera pose from surveyed control points (world coordinates in the scene's frame and their pixel
/// positions): cv::solvePnPRansac to reject mis-picked points, then Levenberg–Marquardt refinement
/// on the inliers (cv::solvePnPRefineLM); the pose's 1σ from the reprojection Jacobian, cov =
/// σ̂²(JᵀJ)⁻¹ with σ̂² = Σr² / (2N − 6).

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/core/camera_model.h"
#include "tirpol/core/image.h"

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

struct CalibrationTarget {
    enum class Kind { Checkerboard, Circles, AsymmetricCircles };
    Kind kind = Kind::Checkerboard;
    int columns = 0;  ///< inner corners (checkerboard) or circles along a row
    int rows = 0;     ///< inner corners or circles down a column
    double spacing_m =
        0.0;  ///< square side; circle pitch; for the asymmetric grid half the pitch along a row

    /// Parses `checkerboard:COLSxROWS:SQUARE_M`, `circles:COLSxROWS:PITCH_M` or
    /// `acircles:COLSxROWS:HALF_PITCH_M` (OpenCV's asymmetric grid). COLSxROWS count inner corners
    /// of a checkerboard (a board of 10×7 squares is 9x6). Throws naming what was expected.
    static CalibrationTarget parse(const std::string& text);
    std::string to_string() const;

    std::size_t point_count() const {
        return static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows);
    }
    /// Feature positions in the target frame, metres, in detection order.
    std::vector<Vec3> object_points() const;
};

/// Feature points of one view in OpenCV pixel coordinates (centre of the top-left pixel at (0, 0)),
/// in the order of CalibrationTarget::object_points().
struct TargetView {
    std::string name;  ///< frame file or label, for messages
    std::vector<Vec2> points_px;
};

/// The outcome of a search for the target in one frame: the view, or why there is none.
struct TargetSearch {
    std::optional<TargetView> view;
    /// Empty when found; else why not, e.g. "only a 6x5 grid of the target's 9x6 inner corners is
    /// in the frame: the board runs off its left edge; …", a grid of another size than the
    /// target's, a flat frame, or no target at all.
    std::string failure;
};

/// Searches a single-channel plane of `width`×`height` values (any units) for `target`. Throws
/// when the plane's size does not match.
TargetSearch search_target(const std::vector<float>& plane, int width, int height,
                           const CalibrationTarget& target, const std::string& name = "");

/// search_target() on every plane, the frames spread over the cores. `names` (optional) label the
/// views.
std::vector<TargetSearch> search_target_views(const std::vector<std::vector<float>>& planes,
                                              int width, int height,
                                              const CalibrationTarget& target,
                                              const std::vector<std::string>& names = {});

/// search_target()'s view: nullopt when the target is not found.
std::optional<TargetView> detect_target(const std::vector<float>& plane, int width, int height,
                                        const CalibrationTarget& target,
                                        const std::string& name = "");

/// detect_target() on every plane, the frames spread over the cores; element i is nullopt where
/// the target was not found in plane i. `names` (optional) label the views.
std::vector<std::optional<TargetView>> detect_target_views(
    const std::vector<std::vector<float>>& planes, int width, int height,
    const CalibrationTarget& target, const std::vector<std::string>& names = {});

struct GeometricCalibrationOptions {
    std::string distortion_model = "standard";  ///< standard (k1 k2 p1 p2 k3), rational, thin_prism
    bool fix_k3 = false;                        ///< keep k3 = 0 (few views, or a narrow lens)
    bool zero_tangential = false;               ///< keep p1 = p2 = 0
    int min_views = 5;                          ///< fewer usable views is an error
    /// Views whose RMS exceeds max(outlier_factor × median view RMS, median + outlier_margin_px)
    /// are flagged (and reported, not dropped: the user decides).
    double outlier_factor = 3.0;
    double outlier_margin_px = 0.25;
    /// All target planes within this angle of each other (rotations about the optical axis aside)
    /// leave the focal length unobservable: an error.
    double min_tilt_spread_deg = 5.0;
};

struct ViewReport {
    std::string name;
    double rms_px = 0.0;
    double tilt_deg = 0.0;  ///< angle between the target normal and the optical axis
    bool outlier = false;
};

struct GeometricCalibrationResult {
    CameraModel model;                         ///< with rms_px, views, std_dev and target filled in
    std::vector<ViewReport> views;             ///< the views used, in input order
    std::vector<std::string> parameter_names;  ///< fx fy cx cy k1 …, the order of model.std_dev
    std::vector<std::string> frames_without_target;
    /// Why the target was not found, one per frames_without_target (TargetSearch::failure).
    std::vector<std::string> why_target_not_found;
};

/// Calibrates from detected views of `target` in images of `width`×`height`. Throws tirpol::Error
/// for too few views, views with the wrong point count, or degenerate geometry (all views
/// parallel).
GeometricCalibrationResult calibrate_geometric(const std::vector<TargetView>& views,
                                               const CalibrationTarget& target, int width,
                                               int height,
                                               const GeometricCalibrationOptions& options = {});

/// Reads each frame, detects the target and calibrates. Frames without the target are listed in the
/// result; if fewer than options.min_views remain, the error names every frame without the target.
GeometricCalibrationResult calibrate_geometric_frames(
    const std::vector<std::filesystem::path>& frames, const CalibrationTarget& target,
    const GeometricCalibrationOptions& options = {});

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

/// Reads a frame for detection: an EXR (channel `counts`, else `S0`) or a PNG/TIFF (8/16-bit,
/// float).
Image read_calibration_frame(const std::filesystem::path& path);

}  // namespace tirpol::calibration
