#include "figures.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"

namespace tirpol::report::detail {

namespace {

const cv::Scalar kBlack(0, 0, 0), kGrey(150, 150, 150), kWhite(255, 255, 255);
constexpr auto kFont = cv::FONT_HERSHEY_SIMPLEX;

void write_png(const std::filesystem::path& path, const cv::Mat& image) {
    AtomicFile file(path);
    bool ok = false;
    try {
        ok = cv::imwrite(file.temp_path().string(), image);
    } catch (const cv::Exception& e) {
        fail("{}: writing PNG failed: {}", path.string(), e.what());
    }
    if (!ok) fail("{}: writing PNG failed (OpenCV could not encode or write the file)", path.string());
    file.commit();
}

cv::Mat read_png(const std::filesystem::path& path) {
    cv::Mat image = cv::imread(path.string(), cv::IMREAD_COLOR);
    if (image.empty()) fail("{}: could not read back the quicklook PNG", path.string());
    return image;
}

std::string tick_label(double v) {
    const double a = std::abs(v);
    if (a != 0.0 && (a < 1e-2 || a >= 1e4)) return fmt::format("{:.2e}", v);
    return fmt::format("{:.3g}", v);
}

void put_text(cv::Mat& canvas, const std::string& text, cv::Point at, double scale = 0.45,
              const cv::Scalar& colour = kBlack) {
    cv::putText(canvas, ascii_text(text), at, kFont, scale, colour, 1, cv::LINE_AA);
}

int text_width(const std::string& text, double scale = 0.45) {
    int baseline = 0;
    return cv::getTextSize(ascii_text(text), kFont, scale, 1, &baseline).width;
}

// Axis frame with ticks: maps data (x in [x0, x1], y in [y0, y1]) to the plot rectangle.
struct Axes {
    cv::Rect box;
    double x0, x1, y0, y1;
    cv::Point map(double x, double y) const {
        return {box.x + static_cast<int>(std::lround((x - x0) / (x1 - x0) * box.width)),
                box.y + box.height - static_cast<int>(std::lround((y - y0) / (y1 - y0) * box.height))};
    }
    void draw(cv::Mat& canvas, const std::string& x_label, const std::string& y_label, int y_ticks = 5) const {
        cv::rectangle(canvas, box, kBlack);
        for (int k = 0; k <= 4; ++k) {
            const double x = x0 + (x1 - x0) * k / 4.0;
            const cv::Point p = map(x, y0);
            cv::line(canvas, p, p + cv::Point(0, 5), kBlack);
            const std::string label = tick_label(x);
            put_text(canvas, label, p + cv::Point(-text_width(label, 0.4) / 2, 20), 0.4);
        }
        for (int k = 0; k < y_ticks; ++k) {
            const double y = y0 + (y1 - y0) * k / (y_ticks - 1.0);
            const cv::Point p = map(x0, y);
            cv::line(canvas, p, p - cv::Point(5, 0), kBlack);
            const std::string label = tick_label(y);
            put_text(canvas, label, p + cv::Point(-8 - text_width(label, 0.4), 5), 0.4);
        }
        put_text(canvas, x_label, {box.x + box.width / 2 - text_width(x_label) / 2, box.y + box.height + 42});
        put_text(canvas, y_label, {box.x - 60, box.y - 10});
    }
};

std::pair<double, double> percentile_range(std::vector<float> values, double lo_p, double hi_p) {
    if (values.empty()) return {0.0, 1.0};
    auto pick = [&](double p) {
        const auto k = static_cast<std::size_t>(p * static_cast<double>(values.size() - 1));
        std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
        return static_cast<double>(values[k]);
    };
    double lo = pick(lo_p), hi = pick(hi_p);
    if (!(hi > lo)) {
        const double w = std::max(std::abs(lo) * 1e-3, 1e-12);
        lo -= w;
        hi += w;
    }
    return {lo, hi};
}

}  // namespace

Plane display_plane(const std::vector<float>& data, int width, int height) {
    const int side = std::max(width, height);
    if (side <= kDisplayMaxSide) return {data, width, height};
    const double f = static_cast<double>(kDisplayMaxSide) / side;
    const int w = std::max(1, static_cast<int>(std::lround(width * f)));
    const int h = std::max(1, static_cast<int>(std::lround(height * f)));
    const cv::Mat src(height, width, CV_32F, const_cast<float*>(data.data()));
    cv::Mat dst;
    cv::resize(src, dst, {w, h}, 0, 0, cv::INTER_AREA);
    return {std::vector<float>(dst.ptr<float>(), dst.ptr<float>() + dst.total()), w, h};
}

std::string ascii_text(const std::string& text) {
    static const std::pair<const char*, const char*> kReplacements[] = {
        {"²", "^2"}, {"·", " "}, {"µ", "u"}, {"°", "deg"}, {"−", "-"}, {"σ", "sigma"}, {"≈", "~"}, {"×", "x"}};
    std::string out;
    for (std::size_t i = 0; i < text.size();) {
        bool replaced = false;
        for (const auto& [from, to] : kReplacements)
            if (text.compare(i, std::strlen(from), from) == 0) {
                out += to;
                i += std::strlen(from);
                replaced = true;
                break;
            }
        if (replaced) continue;
        if (static_cast<unsigned char>(text[i]) < 128) out += text[i];
        ++i;
    }
    return out;
}

std::vector<int> region_colour(std::size_t index) {
    // Tableau 10 (sRGB), as BGR.
    static constexpr int kRgb[10][3] = {{31, 119, 180}, {255, 127, 14}, {44, 160, 44},  {214, 39, 40},
                                         {148, 103, 189}, {140, 86, 75},  {227, 119, 194}, {127, 127, 127},
                                         {188, 189, 34},  {23, 190, 207}};
    const auto& c = kRgb[index % 10];
    return {c[2], c[1], c[0]};
}

std::string region_colour_css(std::size_t index) {
    const auto bgr = region_colour(index);
    return fmt::format("#{:02x}{:02x}{:02x}", bgr[2], bgr[1], bgr[0]);
}

void write_panel(const std::filesystem::path& panel, const std::vector<std::filesystem::path>& parts,
                 const std::vector<Plane>& planes, const std::vector<QuicklookOptions>& options) {
    std::vector<cv::Mat> images;
    int height = 0;
    for (std::size_t i = 0; i < parts.size(); ++i) {
        write_quicklook(parts[i], planes[i].data, planes[i].width, planes[i].height, options[i]);
        images.push_back(read_png(parts[i]));
        height = std::max(height, images.back().rows);
    }
    std::vector<cv::Mat> row;
    for (auto& image : images) {
        cv::Mat padded(height, image.cols, CV_8UC3, kWhite);
        image.copyTo(padded(cv::Rect(0, 0, image.cols, image.rows)));
        row.push_back(padded);
    }
    cv::Mat out;
    cv::hconcat(row, out);
    write_png(panel, out);
}

void write_region_overview(const std::filesystem::path& path, const std::vector<float>& s0, int width, int height,
                           const std::vector<Region>& regions) {
    // Drawn larger than the panels (long side kOverviewSide) so that region names stay legible.
    constexpr int kOverviewSide = 560;
    const double f = static_cast<double>(kOverviewSide) / std::max(width, height);
    std::vector<float> finite;
    for (float v : s0)
        if (std::isfinite(v)) finite.push_back(v);
    const auto [lo, hi] = percentile_range(finite, 0.01, 0.99);
    cv::Mat grey(height, width, CV_8UC1);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float v = s0[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
            grey.at<uchar>(y, x) = std::isfinite(v) ? cv::saturate_cast<uchar>(40.0 + 200.0 * std::clamp((v - lo) / (hi - lo), 0.0, 1.0))
                                                    : uchar{128};
        }
    const cv::Size shown(std::max(1, static_cast<int>(std::lround(width * f))), std::max(1, static_cast<int>(std::lround(height * f))));
    cv::resize(grey, grey, shown, 0, 0, f < 1.0 ? cv::INTER_AREA : cv::INTER_NEAREST);
    cv::cvtColor(grey, grey, cv::COLOR_GRAY2BGR);
    const int pad = 10;
    cv::Mat canvas(grey.rows + 2 * pad, grey.cols + 2 * pad, CV_8UC3, kWhite);
    grey.copyTo(canvas(cv::Rect(pad, pad, grey.cols, grey.rows)));
    for (std::size_t r = 0; r < regions.size(); ++r) {
        const auto c = region_colour(r);
        const cv::Scalar colour(c[0], c[1], c[2]);
        std::vector<cv::Point> pts;
        for (const auto& p : regions[r].polygon)
            pts.emplace_back(pad + static_cast<int>(std::lround((p.x + 0.5) * f)),
                             pad + static_cast<int>(std::lround((p.y + 0.5) * f)));
        cv::polylines(canvas, std::vector<std::vector<cv::Point>>{pts}, true, colour, 2, cv::LINE_AA);
        const cv::Point label = pts.front() + cv::Point(4, 17);
        const std::string name = ascii_text(regions[r].name);
        cv::putText(canvas, name, label, kFont, 0.5, kWhite, 4, cv::LINE_AA);
        cv::putText(canvas, name, label, kFont, 0.5, colour, 1, cv::LINE_AA);
    }
    write_png(path, canvas);
}

void write_scatter(const std::filesystem::path& path, const std::string& title, const std::string& units,
                   const std::vector<ScatterSeries>& series) {
    constexpr std::size_t kMaxPointsPerSeries = 3000;
    std::vector<float> all;
    for (const auto& s : series)
        for (std::size_t i = 0; i < s.measured.size(); ++i)
            if (std::isfinite(s.measured[i]) && std::isfinite(s.simulated[i])) {
                all.push_back(s.measured[i]);
                all.push_back(s.simulated[i]);
            }
    auto [lo, hi] = percentile_range(all, 0.002, 0.998);
    const double margin = 0.05 * (hi - lo);
    lo -= margin;
    hi += margin;

    cv::Mat canvas(500, 520, CV_8UC3, kWhite);
    const Axes axes{{90, 50, 400, 390}, lo, hi, lo, hi};
    const std::string unit_suffix = units.empty() ? "" : " [" + units + "]";
    put_text(canvas, title, {90, 22}, 0.6);
    // 1:1 line, dashed.
    for (int k = 0; k < 40; k += 2) {
        const double a = lo + (hi - lo) * k / 40.0, b = lo + (hi - lo) * (k + 1) / 40.0;
        cv::line(canvas, axes.map(a, a), axes.map(b, b), kGrey, 1, cv::LINE_AA);
    }
    cv::Mat plot = canvas(axes.box);
    for (std::size_t r = 0; r < series.size(); ++r) {
        const auto c = region_colour(r);
        const cv::Vec3b colour(static_cast<uchar>(c[0]), static_cast<uchar>(c[1]), static_cast<uchar>(c[2]));
        const auto& s = series[r];
        const std::size_t stride = std::max<std::size_t>(1, s.measured.size() / kMaxPointsPerSeries);
        for (std::size_t i = 0; i < s.measured.size(); i += stride) {
            if (!std::isfinite(s.measured[i]) || !std::isfinite(s.simulated[i])) continue;
            const cv::Point p = axes.map(s.measured[i], s.simulated[i]) - axes.box.tl();
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const cv::Point q = p + cv::Point(dx, dy);
                    if (q.inside(cv::Rect(0, 0, plot.cols, plot.rows))) plot.at<cv::Vec3b>(q) = colour;
                }
        }
    }
    axes.draw(canvas, "measured" + unit_suffix, "simulated");
    for (std::size_t r = 0; r < series.size(); ++r) {
        const auto c = region_colour(r);
        const cv::Point at(axes.box.x + 10, axes.box.y + 18 + 18 * static_cast<int>(r));
        cv::rectangle(canvas, {at.x, at.y - 9, 10, 10}, cv::Scalar(c[0], c[1], c[2]), cv::FILLED);
        put_text(canvas, series[r].name, at + cv::Point(15, 0), 0.42);
    }
    write_png(path, canvas);
}

void write_histogram(const std::filesystem::path& path, const std::string& title, const std::string& x_label,
                     const std::vector<float>& values, double lo, double hi, const std::vector<double>& markers,
                     double gaussian_mean, double gaussian_sigma) {
    constexpr int kBins = 60;
    std::vector<double> counts(kBins, 0.0);
    std::size_t n = 0;
    for (float v : values) {
        if (!std::isfinite(v)) continue;
        ++n;
        const int b = static_cast<int>(std::floor((v - lo) / (hi - lo) * kBins));
        if (b >= 0 && b < kBins) counts[static_cast<std::size_t>(b)] += 1.0;
    }
    const double bin_width = (hi - lo) / kBins;
    double peak = 0.0;
    for (auto& c : counts) {
        c = n ? c / (static_cast<double>(n) * bin_width) : 0.0;  // density
        peak = std::max(peak, c);
    }
    auto gaussian = [&](double x) {
        const double u = (x - gaussian_mean) / gaussian_sigma;
        return std::exp(-0.5 * u * u) / (gaussian_sigma * std::sqrt(2.0 * std::numbers::pi));
    };
    if (gaussian_sigma > 0.0) peak = std::max(peak, gaussian(gaussian_mean));
    if (!(peak > 0.0)) peak = 1.0;

    cv::Mat canvas(360, 520, CV_8UC3, kWhite);
    const Axes axes{{90, 40, 400, 250}, lo, hi, 0.0, peak * 1.08};
    put_text(canvas, title, {90, 24}, 0.6);
    for (int b = 0; b < kBins; ++b) {
        const cv::Point a = axes.map(lo + b * bin_width, 0.0), c = axes.map(lo + (b + 1) * bin_width, counts[static_cast<std::size_t>(b)]);
        cv::rectangle(canvas, cv::Rect(cv::Point(a.x, c.y), cv::Point(c.x, a.y)), cv::Scalar(180, 130, 70), cv::FILLED);
    }
    if (gaussian_sigma > 0.0) {
        std::vector<cv::Point> curve;
        for (int k = 0; k <= 200; ++k) {
            const double x = lo + (hi - lo) * k / 200.0;
            curve.push_back(axes.map(x, gaussian(x)));
        }
        cv::polylines(canvas, std::vector<std::vector<cv::Point>>{curve}, false, cv::Scalar(40, 40, 200), 2, cv::LINE_AA);
    }
    for (double m : markers) {
        if (m < lo || m > hi) continue;
        cv::line(canvas, axes.map(m, 0.0), axes.map(m, peak * 1.08), kGrey, 1, cv::LINE_AA);
    }
    axes.draw(canvas, x_label, "density", 3);
    write_png(path, canvas);
}

}  // namespace tirpol::report::detail
