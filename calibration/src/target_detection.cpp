#include "tirpol/calibration/target_detection.h"

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

#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/raster_io.h"

namespace tirpol::calibration {

namespace {
/// Robust contrast stretch to [0, 255] (float): percentiles over finite values, so a few hot or
/// dead pixels and the 14-bit range do not squash the target's contrast.
cv::Mat stretched(const std::vector<float>& plane, int width, int height) {
    std::vector<float> finite;
    finite.reserve(plane.size());
    for (float v : plane)
        if (std::isfinite(v)) finite.push_back(v);
    if (finite.size() < plane.size() / 2) return {};
    auto quantile = [&](double q) {
        auto it = finite.begin() +
                  static_cast<std::ptrdiff_t>(q * static_cast<double>(finite.size() - 1));
        std::nth_element(finite.begin(), it, finite.end());
        return *it;
    };
    const float lo = quantile(0.005), hi = quantile(0.995);
    if (!(hi > lo)) return {};
    cv::Mat out(height, width, CV_32F);
    const float scale = 255.0f / (hi - lo);
    for (int y = 0; y < height; ++y) {
        auto* row = out.ptr<float>(y);
        for (int x = 0; x < width; ++x) {
            const float v = plane[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                                  static_cast<std::size_t>(x)];
            row[x] = std::isfinite(v) ? std::clamp((v - lo) * scale, 0.0f, 255.0f) : 127.5f;
        }
    }
    return out;
}

/// Half the smallest distance between neighbouring corners, clamped: cornerSubPix's window must not
/// reach the next corner.
int subpixel_half_window(const std::vector<cv::Point2f>& corners, int columns) {
    double min_d = 1e9;
    for (std::size_t i = 0; i + 1 < corners.size(); ++i)
        if ((static_cast<int>(i) + 1) % columns != 0)
            min_d = std::min(min_d, cv::norm(corners[i + 1] - corners[i]));
    return std::clamp(static_cast<int>(min_d * 0.4), 2, 10);
}

/// Frames at least this many rows high are first searched at half resolution: the sector detector's
/// cost grows with the pixel count, and a board that fills a 512-row frame still has squares of
/// ≥ 10 px at 256 rows. The corners are refined at full resolution either way.
constexpr int kCoarseSearchMinRows = 480;

/// Inner corners by OpenCV's sector-based detector (findChessboardCornersSB: Duda & Frese,
/// "Accurate Detection and Localization of Checkerboard Corners for Calibration", BMVC 2018). It
/// responds to corners whatever the polarity, so a hot-squares board on a cold border is found as
/// is. The quad-based findChessboardCorners is not used: it needs dark squares inside a light
/// border, and on the other polarity its search fails only after every dilation and threshold (3–5
/// s CPU per 640×512 frame, profiled for issue 14) — the fast check passes, since a board is there.
std::optional<std::vector<cv::Point2f>> find_checkerboard_corners(const cv::Mat& image_8u,
                                                                  const cv::Size& size) {
    std::vector<cv::Point2f> corners;
    if (image_8u.rows >= kCoarseSearchMinRows) {
        cv::Mat half;
        cv::resize(image_8u, half, cv::Size(), 0.5, 0.5, cv::INTER_AREA);
        if (cv::findChessboardCornersSB(half, size, corners, cv::CALIB_CB_NORMALIZE_IMAGE)) {
            // Pixel centres: half-resolution pixel i covers full-resolution pixels 2i and 2i + 1.
            for (auto& p : corners) p = 2.0f * p + cv::Point2f(0.5f, 0.5f);
            return corners;
        }
    }
    // Small, blurred or steeply tilted boards: the exhaustive search at full resolution.
    if (cv::findChessboardCornersSB(image_8u, size, corners,
                                    cv::CALIB_CB_NORMALIZE_IMAGE | cv::CALIB_CB_EXHAUSTIVE))
        return corners;
    return std::nullopt;
}

std::optional<std::vector<cv::Point2f>> find_checkerboard(const cv::Mat& image_f,
                                                          const cv::Size& size) {
    cv::Mat image_8u;
    image_f.convertTo(image_8u, CV_8U);
    auto corners = find_checkerboard_corners(image_8u, size);
    if (!corners) return std::nullopt;
    const int half = subpixel_half_window(*corners, size.width);
    cv::cornerSubPix(image_f, *corners, cv::Size(half, half), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 100, 1e-4));
    return corners;
}

/// Circle centres by cv::findCirclesGrid with a blob detector set for thermal frames: after the
/// robust stretch the target's contrast spans 0–255, so the default threshold ladder applies; the
/// discs of a low-resolution frame are a few pixels across and close together (the default 10 px
/// between blobs and 25 px² of area would drop them), tilted views turn them into ellipses
/// (inertia ratio cos(tilt)), and noise roughens their edges (convexity). `hot_discs`: hot discs on
/// a cold plate (a heated plate behind a mask with holes) or the inverse.
std::optional<std::vector<cv::Point2f>> find_circles(const cv::Mat& image_f, const cv::Size& size,
                                                     bool asymmetric, bool hot_discs) {
    cv::Mat image_8u;
    image_f.convertTo(image_8u, CV_8U);
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

std::optional<TargetView> detect_target(const std::vector<float>& plane, int width, int height,
                                        const CalibrationTarget& target, const std::string& name) {
    if (plane.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
        fail("{}: {} values do not fill {}x{}", name, plane.size(), width, height);
    const cv::Mat image = stretched(plane, width, height);
    if (image.empty()) return std::nullopt;  // flat or mostly invalid frame
    const cv::Size size(target.columns, target.rows);
    std::optional<std::vector<cv::Point2f>> found;
    if (target.kind == CalibrationTarget::Kind::Checkerboard) {
        found = find_checkerboard(image, size);  // either polarity
    } else {
        for (bool hot_discs : {true, false}) {
            found = find_circles(
                image, size, target.kind == CalibrationTarget::Kind::AsymmetricCircles, hot_discs);
            if (found) break;
        }
    }
    if (!found) return std::nullopt;
    TargetView view{name, {}};
    view.points_px.reserve(found->size());
    for (const auto& p : *found) view.points_px.emplace_back(p.x, p.y);
    return view;
}

std::vector<std::optional<TargetView>> detect_target_views(
    const std::vector<std::vector<float>>& planes, int width, int height,
    const CalibrationTarget& target, const std::vector<std::string>& names) {
    std::vector<std::optional<TargetView>> out(planes.size());
    std::atomic<std::size_t> next{0};
    std::exception_ptr error;
    std::mutex error_mutex;
    auto worker = [&] {
        for (std::size_t i = next++; i < planes.size(); i = next++) {
            try {
                out[i] = detect_target(planes[i], width, height, target,
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
