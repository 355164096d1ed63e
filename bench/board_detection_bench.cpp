// Checkerboard detection on two sets of 16 synthetic LWIR views
// (tests/calibration/blurred_boards.h): blurred and low-contrast, and a harder set with what an
// uncooled bolometer adds (4 px blur, 6–10 counts, vignetting and gradient, column offsets, stuck
// pixels). tirpol's detect_target() against OpenCV's findChessboardCorners (classic, default flags,
// then cornerSubPix) and findChessboardCornersSB (exhaustive, accuracy), both on a
// percentile-stretched 8-bit copy. Each benchmark runs the 16 views of a set once and reports
// boards found, corner RMS against the true corners and time per view. One iteration only: the
// classic OpenCV search takes seconds on a view it fails
// (--benchmark_filter=-findChessboardCorners/ leaves it out).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <opencv2/calib3d.hpp>
#include <optional>
#include <string>

#include "../tests/calibration/blurred_boards.h"
#include "tirpol/calibration/geometric_calibration.h"

namespace {

using namespace tirpol;
using namespace tirpol::calibration;

constexpr int kViews = 16;
/// A board counts as found when its corners are within this RMS of the truth, px.
constexpr double kFoundRmsPx = 1.0;

const CalibrationTarget& target() {
    static const CalibrationTarget t = CalibrationTarget::parse("checkerboard:9x6:0.05");
    return t;
}

enum class BoardSet { Blurred, Bolometer };

const std::vector<test::BlurredBoard>& views(BoardSet set) {
    auto render = [](auto view) {
        std::vector<test::BlurredBoard> v;
        for (int i = 0; i < kViews; ++i) v.push_back(view(target(), i));
        return v;
    };
    static const std::vector<test::BlurredBoard> blurred = render(test::blurred_board_view);
    static const std::vector<test::BlurredBoard> bolometer = render(test::hard_board_view);
    return set == BoardSet::Blurred ? blurred : bolometer;
}

/// The frame as 8 bits, stretched linearly between its 0.5 % and 99.5 % quantiles: the board's
/// 12–40 counts of contrast then span most of 0–255 (a min/max stretch would let the noise tails
/// set the range, and a plain 14-bit → 8-bit shift leaves the board within 1–3 grey levels).
cv::Mat as_8bit(const std::vector<float>& plane) {
    std::vector<float> sorted = plane;
    std::sort(sorted.begin(), sorted.end());
    const float lo = sorted[sorted.size() / 200];
    const float hi = sorted[sorted.size() - 1 - sorted.size() / 200];
    cv::Mat out(test::kBoardHeight, test::kBoardWidth, CV_8U);
    for (std::size_t i = 0; i < plane.size(); ++i)
        out.data[i] = cv::saturate_cast<uchar>(255.0f * (plane[i] - lo) / (hi - lo));
    return out;
}

std::vector<Vec2> to_vec2(const std::vector<cv::Point2f>& corners) {
    std::vector<Vec2> pts;
    for (const auto& p : corners) pts.emplace_back(p.x, p.y);
    return pts;
}

using Detector = std::optional<std::vector<Vec2>> (*)(const test::BlurredBoard&);

std::optional<std::vector<Vec2>> detect_tirpol(const test::BlurredBoard& b) {
    const auto view =
        detect_target(b.plane, test::kBoardWidth, test::kBoardHeight, target(), "view");
    if (!view || view->points_px.size() != target().point_count()) return std::nullopt;
    return view->points_px;
}

std::optional<std::vector<Vec2>> detect_opencv_classic(const test::BlurredBoard& b) {
    const cv::Mat gray = as_8bit(b.plane);
    std::vector<cv::Point2f> corners;
    if (!cv::findChessboardCorners(gray, cv::Size(target().columns, target().rows), corners,
                                   cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE))
        return std::nullopt;
    cv::cornerSubPix(gray, corners, cv::Size(5, 5), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 50, 1e-3));
    return to_vec2(corners);
}

std::optional<std::vector<Vec2>> detect_opencv_sb(const test::BlurredBoard& b) {
    const cv::Mat gray = as_8bit(b.plane);
    std::vector<cv::Point2f> corners;
    if (!cv::findChessboardCornersSB(gray, cv::Size(target().columns, target().rows), corners,
                                     cv::CALIB_CB_EXHAUSTIVE | cv::CALIB_CB_ACCURACY))
        return std::nullopt;
    return to_vec2(corners);
}

void run_detector(benchmark::State& state, Detector detector, const char* label, BoardSet set) {
    const auto& boards = views(set);  // rendered once, outside the timing
    const char* set_name = set == BoardSet::Blurred ? "blurred" : "bolometer";
    int found = 0;
    double sum2 = 0.0, seconds = 0.0;
    for (auto _ : state) {
        found = 0;
        sum2 = 0.0;
        const auto start = std::chrono::steady_clock::now();
        for (std::size_t i = 0; i < boards.size(); ++i) {
            const test::BlurredBoard& b = boards[i];
            const auto corners = detector(b);
            const double rms = corners ? test::corner_rms_px(b.corners_px, *corners) : -1.0;
            // Per view on stderr, so the table can say which views a detector misses.
            std::fprintf(
                stderr,
                "%s %s view %2zu blur %.1f px contrast %2.0f counts tilt %4.1f deg %s: %s\n", label,
                set_name, i, b.blur_px, b.contrast_counts, b.tilt_deg,
                b.hot_squares ? "hot" : "cold",
                rms < 0 ? "not found" : std::to_string(rms).c_str());
            if (!corners) continue;
            if (rms < kFoundRmsPx) {
                ++found;
                sum2 += rms * rms;
            }
        }
        seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    state.counters["found_of_16"] = found;
    state.counters["corner_rms_px"] = found > 0 ? std::sqrt(sum2 / found) : 0.0;
    state.counters["ms_per_view"] = 1000.0 * seconds / kViews;
}

#define TIRPOL_BOARD_BENCH(name, detector, label, set)                    \
    BENCHMARK_CAPTURE(run_detector, name, detector, label, BoardSet::set) \
        ->Iterations(1)                                                   \
        ->Unit(benchmark::kMillisecond)

TIRPOL_BOARD_BENCH(blurred / tirpol_detect_target, &detect_tirpol, "tirpol", Blurred);
TIRPOL_BOARD_BENCH(blurred / opencv_findChessboardCorners, &detect_opencv_classic,
                   "findChessboardCorners", Blurred);
TIRPOL_BOARD_BENCH(blurred / opencv_findChessboardCornersSB, &detect_opencv_sb,
                   "findChessboardCornersSB", Blurred);
TIRPOL_BOARD_BENCH(bolometer / tirpol_detect_target, &detect_tirpol, "tirpol", Bolometer);
TIRPOL_BOARD_BENCH(bolometer / opencv_findChessboardCorners, &detect_opencv_classic,
                   "findChessboardCorners", Bolometer);
TIRPOL_BOARD_BENCH(bolometer / opencv_findChessboardCornersSB, &detect_opencv_sb,
                   "findChessboardCornersSB", Bolometer);

}  // namespace

BENCHMARK_MAIN();
