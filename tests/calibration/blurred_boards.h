#pragma once
// Synthetic LWIR checkerboard views that are hard to detect, in 640×512 frames rendered by exact
// perspective (a homography of the board plane) with 4×4 supersampled coverage, so the true corners
// are known to ~0.02 px. Two sets of 16 views with the same board poses (tilted 10–50°, both
// polarities):
// - blurred_board_view(): optical blur of 1.5–3 px, a board contrast of 12–40 counts on an
//   8000-count pedestal with 2 counts of temporal noise;
// - hard_board_view(): what an uncooled bolometer adds on a bad night — 4 px of blur, 6–10 counts
//   of contrast (3–5 × the noise), a vignetting fall-off and a tilted gradient ten times the
//   board's contrast, fixed-pattern column offsets and dead (stuck low or high) pixels.

#include <opencv2/imgproc.hpp>
#include <random>
#include <vector>

#include "tirpol/calibration/geometric_calibration.h"
#include "tirpol/core/geometry.h"

namespace tirpol::test {

struct BlurredBoard {
    std::vector<float> plane;      ///< counts, row-major
    std::vector<Vec2> corners_px;  ///< true inner corners (pixel centres at integer + 0)
    double blur_px = 0, contrast_counts = 0, tilt_deg = 0;
    bool hot_squares = true;
};

inline constexpr int kBoardWidth = 640, kBoardHeight = 512;

/// What the camera adds to the board's image, in counts.
struct BoardImaging {
    double blur_px = 1.5;          ///< Gaussian optical blur, sigma
    double contrast_counts = 40;   ///< hot minus cold squares
    bool hot_squares = true;       ///< the squares hotter than the border they are painted on
    double noise_counts = 2.0;     ///< temporal noise, sigma
    double vignetting_counts = 0;  ///< fall-off from the centre to the frame's corners (∝ r²)
    double gradient_counts =
        0;  ///< linear ramp across the frame's width, in direction `gradient_deg`
    double gradient_deg = 0;
    double column_noise_counts = 0;  ///< fixed-pattern offset per column, sigma
    double dead_pixel_fraction = 0;  ///< pixels stuck at 0 or at the 14-bit maximum
};

/// View `i` of 16 of a `target` (checkerboard, inner corners columns × rows), imaged as `imaging`.
/// The pose depends on `i` only.
inline BlurredBoard render_board_view(const calibration::CalibrationTarget& target, int i,
                                      const BoardImaging& imaging) {
    BlurredBoard b;
    b.blur_px = imaging.blur_px;
    b.contrast_counts = imaging.contrast_counts;
    b.hot_squares = imaging.hot_squares;
    b.tilt_deg = 10.0 + 40.0 * ((i * 5) % 16) / 15.0;
    const double axis = 2.0 * kPi * i / 16.0;
    const double fx = 700.0, cx = 320.0, cy = 256.0;
    // Board plane: squares of 1 unit, inner corners at integer (u, v) from (0, 0) to (cols−1,
    // rows−1); the board's border squares extend one unit beyond.
    const double pitch_m = 0.05, distance_m = 1.1 + 0.05 * (i % 3);
    const Vec3 centre(0.5 * (target.columns - 1), 0.5 * (target.rows - 1), 0.0);
    const Mat3 r =
        Eigen::AngleAxisd(deg_to_rad(b.tilt_deg), Vec3(std::cos(axis), std::sin(axis), 0.0))
            .toRotationMatrix();
    const Vec3 shift(0.04 * std::cos(3.0 * axis), 0.03 * std::sin(2.0 * axis), distance_m);
    // Homography board (u, v, 1) → image: K [r1 r2 t] with the board scaled by its pitch.
    Mat3 k;
    k << fx, 0, cx, 0, fx, cy, 0, 0, 1;
    Mat3 m;
    m.col(0) = r.col(0) * pitch_m;
    m.col(1) = r.col(1) * pitch_m;
    m.col(2) = shift - r * centre * pitch_m;
    const Mat3 h = k * m, h_inv = h.inverse();
    for (int v = 0; v < target.rows; ++v)
        for (int u = 0; u < target.columns; ++u) {
            const Vec3 p = h * Vec3(u, v, 1.0);
            b.corners_px.emplace_back(p.x() / p.z(), p.y() / p.z());
        }
    cv::Mat img(kBoardHeight, kBoardWidth, CV_32F);
    for (int y = 0; y < kBoardHeight; ++y)
        for (int x = 0; x < kBoardWidth; ++x) {
            double hot = 0.0;
            for (int sy = 0; sy < 4; ++sy)
                for (int sx = 0; sx < 4; ++sx) {
                    const Vec3 q =
                        h_inv * Vec3(x - 0.5 + (sx + 0.5) / 4, y - 0.5 + (sy + 0.5) / 4, 1);
                    const double u = q.x() / q.z(), v = q.y() / q.z();
                    const bool in_board = u > -1 && v > -1 && u < target.columns && v < target.rows;
                    const bool even =
                        (static_cast<int>(std::floor(u)) + static_cast<int>(std::floor(v))) % 2 ==
                        0;
                    hot += in_board && even == b.hot_squares ? 1.0 : 0.0;
                }
            // Outside the board: the cold (or warm) frame the squares are painted on.
            img.at<float>(y, x) = static_cast<float>(8000.0 + b.contrast_counts * hot / 16.0);
        }
    cv::GaussianBlur(img, img, cv::Size(0, 0), b.blur_px);
    std::mt19937 rng(1000u + static_cast<unsigned>(i));
    std::normal_distribution<float> noise(0.0f, static_cast<float>(imaging.noise_counts));
    for (int y = 0; y < kBoardHeight; ++y)
        for (int x = 0; x < kBoardWidth; ++x) img.at<float>(y, x) += noise(rng);
    if (imaging.vignetting_counts != 0.0 || imaging.gradient_counts != 0.0) {
        const double r2_corner = cx * cx + cy * cy;
        const double gx = std::cos(deg_to_rad(imaging.gradient_deg)) / kBoardWidth;
        const double gy = std::sin(deg_to_rad(imaging.gradient_deg)) / kBoardWidth;
        for (int y = 0; y < kBoardHeight; ++y)
            for (int x = 0; x < kBoardWidth; ++x) {
                const double dx = x - cx, dy = y - cy;
                img.at<float>(y, x) += static_cast<float>(
                    -imaging.vignetting_counts * (dx * dx + dy * dy) / r2_corner +
                    imaging.gradient_counts * (dx * gx + dy * gy));
            }
    }
    if (imaging.column_noise_counts > 0.0) {
        std::normal_distribution<float> column(0.0f,
                                               static_cast<float>(imaging.column_noise_counts));
        for (int x = 0; x < kBoardWidth; ++x) {
            const float offset = column(rng);
            for (int y = 0; y < kBoardHeight; ++y) img.at<float>(y, x) += offset;
        }
    }
    if (imaging.dead_pixel_fraction > 0.0) {
        const auto dead =
            static_cast<int>(imaging.dead_pixel_fraction * kBoardWidth * kBoardHeight);
        std::uniform_int_distribution<int> px(0, kBoardWidth * kBoardHeight - 1);
        for (int d = 0; d < dead; ++d)
            reinterpret_cast<float*>(img.data)[px(rng)] = d % 2 == 0 ? 0.0f : 16383.0f;
    }
    b.plane.assign(img.begin<float>(), img.end<float>());
    return b;
}

/// View `i` of 16: blur 1.5–3 px, contrast 12–40 counts, polarity alternating.
inline BlurredBoard blurred_board_view(const calibration::CalibrationTarget& target, int i) {
    BoardImaging imaging;
    imaging.blur_px = 1.5 + 0.5 * (i % 4);
    imaging.contrast_counts = i % 8 < 4 ? 40.0 : 12.0 + 4.0 * (i % 4);
    imaging.hot_squares = i % 2 == 0;
    return render_board_view(target, i, imaging);
}

/// View `i` of 16 of the harder set: blur 4 px, contrast 6, 8 or 10 counts, polarity alternating,
/// a vignetting fall-off of 60 counts to the corners, a 40-count gradient across the frame in a
/// direction that turns with `i`, column offsets of 1.5 counts (sigma) and 0.05 % dead pixels.
inline BlurredBoard hard_board_view(const calibration::CalibrationTarget& target, int i) {
    BoardImaging imaging;
    imaging.blur_px = 4.0;
    imaging.contrast_counts = 6.0 + 2.0 * (i % 3);
    imaging.hot_squares = i % 2 == 0;
    imaging.vignetting_counts = 60.0;
    imaging.gradient_counts = 40.0;
    imaging.gradient_deg = 22.5 * i;
    imaging.column_noise_counts = 1.5;
    imaging.dead_pixel_fraction = 0.0005;
    return render_board_view(target, i, imaging);
}

/// RMS distance from each true corner to the nearest detected one (the board's symmetric
/// orderings make the detection order ambiguous), px.
inline double corner_rms_px(const std::vector<Vec2>& truth, const std::vector<Vec2>& found) {
    double sum2 = 0.0;
    for (const Vec2& t : truth) {
        double best = 1e30;
        for (const Vec2& f : found) best = std::min(best, (f - t).squaredNorm());
        sum2 += best;
    }
    return std::sqrt(sum2 / static_cast<double>(truth.size()));
}

}  // namespace tirpol::test
