#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>
#include <thread>

#include "checkerboard_search.h"
#include "thermal_frame_conditioning.h"
#include "tirpol/calibration/geometric_calibration.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"

namespace tirpol::calibration {

namespace {
/// Circle centres by cv::findCirclesGrid with a blob detector set for thermal frames: after the
/// robust stretch the target's contrast spans 0–255, so the default threshold ladder applies; the
/// discs of a low-resolution frame are a few pixels across and close together (the default 10 px
/// between blobs and 25 px² of area would drop them), tilted views turn them into ellipses
/// (inertia ratio cos(tilt)), and noise roughens their edges (convexity). `hot_discs`: hot discs on
/// a cold plate (a heated plate behind a mask with holes) or the inverse.
std::optional<std::vector<cv::Point2f>> find_circles(const cv::Mat& image_8u, const cv::Size& size,
                                                     bool asymmetric, bool hot_discs) {
    cv::SimpleBlobDetector::Params params;
    params.minDistBetweenBlobs = 2.0f;
    params.minArea = 6.0f;
    params.maxArea = static_cast<float>(image_8u.total()) * 0.05f;
    params.minInertiaRatio = 0.25f;  // boards tilted up to ~75°
    params.minConvexity = 0.85f;
    params.blobColor = hot_discs ? 255 : 0;
    const auto detector = cv::SimpleBlobDetector::create(params);
    std::vector<cv::Point2f> centres;
    const int grid = asymmetric ? cv::CALIB_CB_ASYMMETRIC_GRID : cv::CALIB_CB_SYMMETRIC_GRID;
    // The plain search first (fast); the clustering one copes with stronger perspective.
    for (int flags : {grid, grid | cv::CALIB_CB_CLUSTERING})
        if (cv::findCirclesGrid(image_8u, size, centres, flags, detector)) return centres;
    return std::nullopt;
}
}  // namespace

TargetSearch search_target(const std::vector<float>& plane, int width, int height,
                           const CalibrationTarget& target, const std::string& name) {
    if (plane.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
        fail("{}: {} values do not fill {}x{}", name, plane.size(), width, height);
    TargetSearch search;
    cv::Mat image = detail::finite_image(plane, width, height, search.failure);
    if (image.empty()) return search;
    const cv::Mat image_8u = detail::stretch_to_8bit(image);
    if (image_8u.empty()) {
        search.failure = "the frame is flat (its 0.5th and 99.5th percentiles are equal)";
        return search;
    }
    const cv::Size size(target.columns, target.rows);
    std::optional<std::vector<cv::Point2f>> found;
    if (target.kind == CalibrationTarget::Kind::Checkerboard) {
        found = detail::find_checkerboard(image_8u, size, false);
        if (!found) {
            // Only when the frame as it is fails, so that it cannot move the corners of a board
            // found without it: without it a board of 6–10 counts under a 100-count vignetting and
            // gradient, with column noise and stuck pixels, was found in 0 of
            // bench/board_detection_bench's 16 views, with it in 16.
            detail::replace_stuck_pixels(image);
            detail::remove_column_offsets(image);
            detail::subtract_background(image);
            const cv::Mat conditioned_8u = detail::stretch_to_8bit(image);
            if (!conditioned_8u.empty()) {
                found = detail::find_checkerboard(conditioned_8u, size, true);
                if (!found) search.failure = detail::why_no_checkerboard(conditioned_8u, size);
            } else {
                search.failure = detail::why_no_checkerboard(image_8u, size);
            }
        }
    } else {
        for (bool hot_discs : {true, false}) {
            found =
                find_circles(image_8u, size,
                             target.kind == CalibrationTarget::Kind::AsymmetricCircles, hot_discs);
            if (found) break;
        }
        if (!found) search.failure = "no circle grid found, hot or cold discs";
    }
    if (!found) return search;
    if (target.kind == CalibrationTarget::Kind::Checkerboard)
        detail::refine_small_squares(image, size, *found);
    search.view = TargetView{name, {}};
    search.view->points_px.reserve(found->size());
    for (const auto& p : *found) search.view->points_px.emplace_back(p.x, p.y);
    return search;
}

std::optional<TargetView> detect_target(const std::vector<float>& plane, int width, int height,
                                        const CalibrationTarget& target, const std::string& name) {
    return search_target(plane, width, height, target, name).view;
}

std::vector<TargetSearch> search_target_views(const std::vector<std::vector<float>>& planes,
                                              int width, int height,
                                              const CalibrationTarget& target,
                                              const std::vector<std::string>& names) {
    std::vector<TargetSearch> out(planes.size());
    std::atomic<std::size_t> next{0};
    std::exception_ptr error;
    std::mutex error_mutex;
    auto worker = [&] {
        for (std::size_t i = next++; i < planes.size(); i = next++) {
            try {
                out[i] = search_target(planes[i], width, height, target,
                                       i < names.size() ? names[i] : fmt::format("view {}", i));
            } catch (...) {
                const std::lock_guard lock(error_mutex);
                if (!error) error = std::current_exception();
            }
        }
    };
    const unsigned threads =
        std::clamp(std::thread::hardware_concurrency(), 1u,
                   static_cast<unsigned>(std::max<std::size_t>(planes.size(), 1)));
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
    if (error) std::rethrow_exception(error);
    return out;
}

std::vector<std::optional<TargetView>> detect_target_views(
    const std::vector<std::vector<float>>& planes, int width, int height,
    const CalibrationTarget& target, const std::vector<std::string>& names) {
    std::vector<std::optional<TargetView>> out;
    out.reserve(planes.size());
    for (auto& search : search_target_views(planes, width, height, target, names))
        out.push_back(std::move(search.view));
    return out;
}

Image read_calibration_frame(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".exr") {
        Image image = read_exr(path);
        for (const char* channel : {"counts", "S0"})
            if (image.has_channel(channel)) {
                Image single(image.width(), image.height());
                single.set_channel("counts", image.channel(channel));
                return single;
            }
        fail("{}: no 'counts' or 'S0' channel to find the calibration target in", path.string());
    }
    return read_raw_image(path, "counts");
}

}  // namespace tirpol::calibration
