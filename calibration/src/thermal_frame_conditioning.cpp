#include "thermal_frame_conditioning.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace tirpol::calibration::detail {

namespace {
/// Values at quantiles `q_low` and `q_high` of a CV_32F image.
std::pair<float, float> quantiles(const cv::Mat& image, double q_low, double q_high) {
    std::vector<float> values(image.begin<float>(), image.end<float>());
    auto at = [&](double q) {
        const auto it = values.begin() +
                        static_cast<std::ptrdiff_t>(q * static_cast<double>(values.size() - 1));
        std::nth_element(values.begin(), it, values.end());
        return *it;
    };
    const float low = at(q_low);
    return {low, at(q_high)};
}

constexpr double kStretchQuantile = 0.005;
}  // namespace

cv::Mat finite_image(const std::vector<float>& plane, int width, int height, std::string& failure) {
    std::vector<float> finite;
    finite.reserve(plane.size());
    for (float v : plane)
        if (std::isfinite(v)) finite.push_back(v);
    if (finite.size() < plane.size() / 2) {
        failure = fmt::format("only {} of {} pixels are finite; expected at least half",
                              finite.size(), plane.size());
        return {};
    }
    const auto mid = finite.begin() + static_cast<std::ptrdiff_t>(finite.size() / 2);
    std::nth_element(finite.begin(), mid, finite.end());
    const float fill = *mid;
    cv::Mat out(height, width, CV_32F);
    auto* dst = out.ptr<float>();
    for (std::size_t i = 0; i < plane.size(); ++i)
        dst[i] = std::isfinite(plane[i]) ? plane[i] : fill;
    return out;
}

void replace_stuck_pixels(cv::Mat& image) {
    const auto [low, high] = quantiles(image, kStretchQuantile, 1.0 - kStretchQuantile);
    cv::Mat median;
    cv::medianBlur(image, median, 3);
    const cv::Mat stuck = cv::abs(image - median) > static_cast<double>(high - low);
    median.copyTo(image, stuck);
}

void remove_column_offsets(cv::Mat& image) {
    cv::Mat running_mean;
    cv::blur(image, running_mean, cv::Size(15, 1), cv::Point(-1, -1), cv::BORDER_REFLECT);
    const cv::Mat high_pass = image - running_mean;
    std::vector<float> column(static_cast<std::size_t>(image.rows));
    for (int x = 0; x < image.cols; ++x) {
        for (int y = 0; y < image.rows; ++y)
            column[static_cast<std::size_t>(y)] = high_pass.at<float>(y, x);
        const auto mid = column.begin() + static_cast<std::ptrdiff_t>(column.size() / 2);
        std::nth_element(column.begin(), mid, column.end());
        image.col(x) -= *mid;
    }
}

void subtract_background(cv::Mat& image) {
    cv::Mat background;
    const double sigma_px = std::max(32.0, std::max(image.cols, image.rows) / 20.0);
    cv::GaussianBlur(image, background, cv::Size(0, 0), sigma_px, sigma_px, cv::BORDER_REFLECT);
    image -= background;
}

cv::Mat stretch_to_8bit(const cv::Mat& image) {
    const auto [low, high] = quantiles(image, kStretchQuantile, 1.0 - kStretchQuantile);
    if (!(high > low)) return {};
    cv::Mat out;
    const double scale = 255.0 / static_cast<double>(high - low);
    image.convertTo(out, CV_8U, scale, -static_cast<double>(low) * scale);  // saturates
    return out;
}

}  // namespace tirpol::calibration::detail
