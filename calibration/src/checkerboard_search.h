#pragma once
// Finding a checkerboard's inner corners in a conditioned 8-bit thermal frame.

#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

namespace tirpol::calibration::detail {

/// Inner corners of a checkerboard of `size` (columns × rows of inner corners) in `image_8u`, to
/// sub-pixel accuracy, in OpenCV's order; nullopt with `failure` saying why when not found: only
/// part of the board visible (and at which edges of the frame it runs off), a grid of another
/// size, or no checkerboard at all.
std::optional<std::vector<cv::Point2f>> find_checkerboard(const cv::Mat& image_8u,
                                                          const cv::Size& size,
                                                          std::string& failure);

}  // namespace tirpol::calibration::detail
