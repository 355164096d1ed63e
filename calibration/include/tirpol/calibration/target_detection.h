#pragma once
/// \file target_detection.h
/// Finding a calibration target in a thermal frame: 14-bit counts, low contrast, blur, hot-on-cold
/// or cold-on-hot. The frame is contrast-stretched robustly (0.5th–99.5th percentile → 0–255, NaN
/// and dead pixels ignored) before OpenCV's detectors. Checkerboards: the sector-based detector
/// (either polarity; frames ≥ 480 rows are searched at half resolution first), corners refined to
/// sub-pixel on the full-resolution stretched float image (cv::cornerSubPix). Circle grids: both
/// polarities are tried; centres are cv::findCirclesGrid's blob centroids.

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

/// Detects `target` in a single-channel plane of `width`×`height` values (any units). Returns
/// nullopt when the target is not found.
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
