#pragma once
/// \file target_detection.h
/// Finding a calibration target in a thermal frame: 14-bit counts, low contrast, blur, hot-on-cold
/// or cold-on-hot. The frame is contrast-stretched robustly (0.5th–99.5th percentile → 0–255, NaN
/// pixels filled with the frame's median) before OpenCV's detectors. Checkerboards: OpenCV's
/// sector-based detector at full resolution with its own sub-pixel refinement (CALIB_CB_ACCURACY),
/// either polarity; when that fails, again after removing stuck pixels, column offsets and the
/// large-scale background (vignetting, gradients), then with the exhaustive search. Squares under
/// 16 px (a 160×120 core's view) are refined further by cv::cornerSubPix.
/// Circle grids: both polarities are tried; centres are cv::findCirclesGrid's blob centroids.
/// docs/camera-geometry.md has the measurements behind each choice.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/calibration/calibration_target.h"
#include "tirpol/core/image.h"

namespace tirpol::calibration {

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

/// Reads a frame for detection: an EXR (channel `counts`, else `S0`) or a PNG/TIFF (8/16-bit,
/// float).
Image read_calibration_frame(const std::filesystem::path& path);

}  // namespace tirpol::calibration
