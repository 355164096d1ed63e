#include "checkerboard_search.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

namespace tirpol::calibration::detail {

namespace {
/// Squares smaller than this (px, between neighbouring inner corners) are refined by cornerSubPix.
constexpr double kSmallSquarePx = 16.0;
}  // namespace

/// Why no board of `size` was found, from the largest grid of at least 3×3 inner corners that the
/// sector detector finds (CALIB_CB_LARGER): a smaller grid near the frame's edges is a board
/// running off the frame; one elsewhere is a board partly occluded or too faint; a grid of another
/// shape is a target of another size than the one named.
std::string why_no_checkerboard(const cv::Mat& image_8u, const cv::Size& size) {
    const cv::Size smallest(std::min(3, size.width), std::min(3, size.height));
    std::vector<cv::Point2f> corners;
    cv::Mat meta;
    if (!cv::findChessboardCornersSB(image_8u, smallest, corners, cv::CALIB_CB_LARGER, meta) ||
        meta.empty())
        return "no checkerboard found";
    // meta is rows × columns of the grid found, which may be the target turned by 90°.
    const int found_long = std::max(meta.cols, meta.rows),
              found_short = std::min(meta.cols, meta.rows);
    const int want_long = std::max(size.width, size.height),
              want_short = std::min(size.width, size.height);
    const std::string found_text = fmt::format("{}x{}", meta.cols, meta.rows);
    if (found_long == want_long && found_short == want_short)
        return fmt::format(
            "the {}x{} grid was found only by the search for any grid of at least 3x3 corners: the "
            "board is too faint or blurred for the exact search",
            size.width, size.height);
    if (found_long > want_long || found_short > want_short)
        return fmt::format(
            "a {} grid of inner corners found, not the target's {}x{}: check the target's size "
            "(inner corners, one fewer than squares, each way)",
            found_text, size.width, size.height);
    // The board's outer squares reach one square beyond its outer inner corners.
    const cv::Rect bounds = cv::boundingRect(corners);
    const double square_px = std::sqrt(static_cast<double>(bounds.area()) /
                                       std::max(1, (meta.cols - 1) * (meta.rows - 1)));
    const double margin_px = 1.5 * square_px;
    std::vector<std::string> edges;
    if (bounds.x < margin_px) edges.emplace_back("left");
    if (bounds.x + bounds.width > image_8u.cols - 1 - margin_px) edges.emplace_back("right");
    if (bounds.y < margin_px) edges.emplace_back("top");
    if (bounds.y + bounds.height > image_8u.rows - 1 - margin_px) edges.emplace_back("bottom");
    if (edges.empty())
        return fmt::format(
            "only a {} grid of the target's {}x{} inner corners found: part of the board is "
            "occluded, or too faint or blurred",
            found_text, size.width, size.height);
    std::string where = edges.front();
    for (std::size_t i = 1; i < edges.size(); ++i)
        where += (i + 1 == edges.size() ? " and " : ", ") + edges[i];
    return fmt::format(
        "only a {} grid of the target's {}x{} inner corners is in the frame: the board runs off "
        "its {} edge{}; aim so that the whole board is in view",
        found_text, size.width, size.height, where, edges.size() > 1 ? "s" : "");
}

std::optional<std::vector<cv::Point2f>> find_checkerboard(const cv::Mat& image_8u,
                                                          const cv::Size& size, bool exhaustive) {
    // OpenCV's sector-based detector (Duda & Frese, "Accurate Detection and Localization of
    // Checkerboard Corners for Calibration", BMVC 2018) at full resolution: it responds to corners
    // of either polarity (a hot board on a cold border or the inverse), and CALIB_CB_ACCURACY
    // refines them on the full-resolution image (measured better than cv::cornerSubPix after it,
    // docs/camera-geometry.md). CALIB_CB_NORMALIZE_IMAGE (histogram equalisation) is not used: on
    // the blurred low-contrast views of bench/board_detection_bench it lost 4 of 16 boards; the
    // stretch has already spread the board over 0–255.
    std::vector<cv::Point2f> corners;
    if (cv::findChessboardCornersSB(image_8u, size, corners, cv::CALIB_CB_ACCURACY)) return corners;
    if (exhaustive && cv::findChessboardCornersSB(image_8u, size, corners,
                                                  cv::CALIB_CB_ACCURACY | cv::CALIB_CB_EXHAUSTIVE))
        return corners;
    return std::nullopt;
}

void refine_small_squares(const cv::Mat& image, const cv::Size& size,
                          std::vector<cv::Point2f>& corners) {
    double min_spacing_px = 1e9;
    for (std::size_t i = 0; i + 1 < corners.size(); ++i)
        if ((static_cast<int>(i) + 1) % size.width != 0)
            min_spacing_px = std::min(min_spacing_px, cv::norm(corners[i + 1] - corners[i]));
    if (min_spacing_px >= kSmallSquarePx) return;
    // The window must not reach the next corner.
    const int half = std::clamp(static_cast<int>(min_spacing_px * 0.4), 2, 10);
    cv::cornerSubPix(image, corners, cv::Size(half, half), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 100, 1e-4));
}

}  // namespace tirpol::calibration::detail
