#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/quicklook.h"

namespace tirpol {

std::vector<double> nice_ticks(double lo, double hi, int target) {
    std::vector<double> ticks;
    if (!(hi > lo) || target < 1) return ticks;
    const double raw = (hi - lo) / target;
    const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
    double step = magnitude;
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * magnitude >= raw) {
            step = m * magnitude;
            break;
        }
    for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + 1e-9 * step; t += step)
        ticks.push_back(std::abs(t) < 1e-12 * step ? 0.0 : t);
    return ticks;
}

namespace {
std::string tick_label(double v, double step) {
    const int decimals = std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    return buf;
}
}  // namespace

void write_line_plot(const std::filesystem::path& path, const std::vector<PlotSeries>& series,
                     const LinePlotOptions& options) {
    if (series.empty()) fail("{}: a plot needs at least one series", path.string());
    double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
    for (const auto& s : series) {
        if (s.x.size() != s.y.size())
            fail("{}: series \"{}\" has {} x values but {} y values", path.string(), s.label,
                 s.x.size(), s.y.size());
        for (std::size_t i = 0; i < s.x.size(); ++i) {
            if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
            x_lo = std::min(x_lo, s.x[i]);
            x_hi = std::max(x_hi, s.x[i]);
            y_lo = std::min(y_lo, s.y[i]);
            y_hi = std::max(y_hi, s.y[i]);
        }
    }
    if (!std::isfinite(x_lo)) fail("{}: no finite data to plot", path.string());
    const double y_pad = 0.05 * std::max(y_hi - y_lo, 1e-12);
    x_lo = options.x_min.value_or(x_lo);
    x_hi = options.x_max.value_or(x_hi);
    y_lo = options.y_min.value_or(y_lo - y_pad);
    y_hi = options.y_max.value_or(y_hi + y_pad);
    if (!(x_hi > x_lo)) x_hi = x_lo + 1.0;
    if (!(y_hi > y_lo)) y_hi = y_lo + 1.0;

    const int w = std::max(300, options.width), h = std::max(200, options.height);
    cv::Mat img(h, w, CV_8UC3, cv::Scalar(255, 255, 255));
    const int left = 90, right = w - 30, top = 50, bottom = h - 70;
    const auto px = [&](double x) { return left + (x - x_lo) / (x_hi - x_lo) * (right - left); };
    const auto py = [&](double y) { return bottom - (y - y_lo) / (y_hi - y_lo) * (bottom - top); };
    const auto pt = [](double x, double y) {
        return cv::Point(static_cast<int>(std::lround(x)), static_cast<int>(std::lround(y)));
    };
    constexpr int kShift = 4;
    const auto sub = [](double x, double y) {
        return cv::Point(static_cast<int>(std::lround(x * (1 << kShift))),
                         static_cast<int>(std::lround(y * (1 << kShift))));
    };
    const cv::Scalar black(0, 0, 0), grid(225, 225, 225);
    const int font = cv::FONT_HERSHEY_SIMPLEX;

    const auto xt = nice_ticks(x_lo, x_hi, 8), yt = nice_ticks(y_lo, y_hi, 6);
    const double xs = xt.size() > 1 ? xt[1] - xt[0] : 1.0, ys = yt.size() > 1 ? yt[1] - yt[0] : 1.0;
    for (double t : xt) {
        cv::line(img, pt(px(t), top), pt(px(t), bottom), grid, 1, cv::LINE_AA);
        const std::string s = tick_label(t, xs);
        int base = 0;
        const cv::Size sz = cv::getTextSize(s, font, 0.45, 1, &base);
        cv::putText(img, s, pt(px(t) - sz.width / 2.0, bottom + 20), font, 0.45, black, 1,
                    cv::LINE_AA);
    }
    for (double t : yt) {
        cv::line(img, pt(left, py(t)), pt(right, py(t)), grid, 1, cv::LINE_AA);
        const std::string s = tick_label(t, ys);
        int base = 0;
        const cv::Size sz = cv::getTextSize(s, font, 0.45, 1, &base);
        cv::putText(img, s, pt(left - 8 - sz.width, py(t) + sz.height / 2.0), font, 0.45, black, 1,
                    cv::LINE_AA);
    }
    if (options.zero_line && y_lo < 0.0 && y_hi > 0.0)
        cv::line(img, pt(left, py(0.0)), pt(right, py(0.0)), cv::Scalar(120, 120, 120), 1,
                 cv::LINE_AA);
    cv::rectangle(img, pt(left, top), pt(right, bottom), black, 1);

    int base = 0;
    const cv::Size title_size = cv::getTextSize(options.title, font, 0.65, 1, &base);
    cv::putText(img, options.title, pt((w - title_size.width) / 2.0, 30), font, 0.65, black, 1,
                cv::LINE_AA);
    const cv::Size xl = cv::getTextSize(options.x_label, font, 0.55, 1, &base);
    cv::putText(img, options.x_label, pt((left + right - xl.width) / 2.0, h - 22), font, 0.55,
                black, 1, cv::LINE_AA);
    if (!options.y_label.empty()) {
        // Draw the y label horizontally on a strip, then rotate it by 90° counter-clockwise.
        const cv::Size yl = cv::getTextSize(options.y_label, font, 0.55, 1, &base);
        cv::Mat strip(yl.height + base + 6, yl.width + 6, CV_8UC3, cv::Scalar(255, 255, 255));
        cv::putText(strip, options.y_label, cv::Point(3, yl.height + 3), font, 0.55, black, 1,
                    cv::LINE_AA);
        cv::Mat rotated;
        cv::rotate(strip, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
        const int x0 = 8, y0 = std::max(0, (top + bottom - rotated.rows) / 2);
        if (y0 + rotated.rows <= h && x0 + rotated.cols <= w)
            rotated.copyTo(img(cv::Rect(x0, y0, rotated.cols, rotated.rows)));
    }

    cv::Mat plot_area = img(cv::Rect(left, top, right - left + 1, bottom - top + 1));
    for (const auto& s : series) {
        const cv::Scalar colour(s.rgb[2], s.rgb[1], s.rgb[0]);
        for (std::size_t i = 0; i + 1 < s.x.size(); ++i) {
            if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i]) || !std::isfinite(s.x[i + 1]) ||
                !std::isfinite(s.y[i + 1]))
                continue;
            if (s.dashed && i % 2 == 1) continue;
            // Sub-pixel end points (4 fractional bits) so that shallow curves do not look stepped.
            cv::line(plot_area, sub(px(s.x[i]) - left, py(s.y[i]) - top),
                     sub(px(s.x[i + 1]) - left, py(s.y[i + 1]) - top), colour, 2, cv::LINE_AA,
                     kShift);
        }
        if (s.markers)
            for (std::size_t i = 0; i < s.x.size(); ++i)
                if (std::isfinite(s.x[i]) && std::isfinite(s.y[i]))
                    cv::circle(plot_area, pt(px(s.x[i]) - left, py(s.y[i]) - top), 3, colour, -1,
                               cv::LINE_AA);
    }

    // Legend, top right inside the axes.
    int legend_w = 0;
    for (const auto& s : series)
        legend_w = std::max(legend_w, cv::getTextSize(s.label, font, 0.5, 1, &base).width);
    const int row = 22, legend_h = row * static_cast<int>(series.size()) + 6;
    const int lx = right - legend_w - 60;
    const int ly = top + 10 +
                   static_cast<int>(std::clamp(options.legend_y_fraction, 0.0, 1.0) *
                                    (bottom - top - 20 - legend_h));
    cv::rectangle(img, pt(lx - 8, ly - 4),
                  pt(right - 8, ly + row * static_cast<int>(series.size()) + 2),
                  cv::Scalar(255, 255, 255), -1);
    cv::rectangle(img, pt(lx - 8, ly - 4),
                  pt(right - 8, ly + row * static_cast<int>(series.size()) + 2), grid, 1);
    for (std::size_t i = 0; i < series.size(); ++i) {
        const auto& s = series[i];
        const cv::Scalar colour(s.rgb[2], s.rgb[1], s.rgb[0]);
        const int y = ly + row * static_cast<int>(i) + row / 2;
        cv::line(img, pt(lx, y), pt(lx + 36, y), colour, 2, cv::LINE_AA);
        cv::putText(img, s.label, pt(lx + 44, y + 5), font, 0.5, black, 1, cv::LINE_AA);
    }

    std::vector<unsigned char> png;
    if (!cv::imencode(".png", img, png)) fail("{}: PNG encoding failed", path.string());
    write_file_atomic(path,
                      std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
}

}  // namespace tirpol
