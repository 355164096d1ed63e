#pragma once
// Finding a checkerboard's inner corners in a conditioned 8-bit thermal frame.

#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

namespace tirpol::calibration::detail {

/// Inner corners of a checkerboard of `size` (columns × rows of inner corners) in `image_8u`, to
/// sub-pixel accuracy, in OpenCV's order; nullopt when not found. `exhaustive`: when the plain
/// search fails, also the exhaustive one (slower; steep, small or faint boards).
std::optional<std::vector<cv::Point2f>> find_checkerboard(const cv::Mat& image_8u,
                                                          const cv::Size& size, bool exhaustive);

/// Refines corners of a board whose squares are smaller than 16 px with cv::cornerSubPix on the
/// (float) frame `image`: there it was measured more accurate than the sector detector's own
/// refinement, on larger squares less (docs/camera-geometry.md).
void refine_small_squares(const cv::Mat& image, const cv::Size& size,
                          std::vector<cv::Point2f>& corners);

/// Why find_checkerboard() found no board of `size` in `image_8u`: only part of the board visible
/// (and at which edges of the frame it runs off), a grid of another size, or no checkerboard.
std::string why_no_checkerboard(const cv::Mat& image_8u, const cv::Size& size);

}  // namespace tirpol::calibration::detail
