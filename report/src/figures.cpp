#include "figures.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"

namespace tirpol::report::detail {

namespace {

const cv::Scalar kWhite(255, 255, 255);

void write_png(const std::filesystem::path& path, const cv::Mat& image) {
    AtomicFile file(path);
    bool ok = false;
    try {
        ok = cv::imwrite(file.temp_path().string(), image);
    } catch (const cv::Exception& e) {
        fail("{}: writing PNG failed: {}", path.string(), e.what());
    }
    if (!ok)
        fail("{}: writing PNG failed (OpenCV could not encode or write the file)", path.string());
    file.commit();
}

cv::Mat read_png(const std::filesystem::path& path) {
    cv::Mat image = cv::imread(path.string(), cv::IMREAD_COLOR);
    if (image.empty()) fail("{}: could not read back the quicklook PNG", path.string());
    return image;
}

}  // namespace

std::pair<double, double> percentile_range(std::vector<float> values, double lo_p, double hi_p) {
    if (values.empty()) return {0.0, 1.0};
    auto pick = [&](double p) {
        const auto k = static_cast<std::size_t>(p * static_cast<double>(values.size() - 1));
        std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k),
                         values.end());
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

std::vector<int> region_colour(std::size_t index) {
    // Tableau 10 (sRGB), as BGR.
    static constexpr int kRgb[10][3] = {
        {31, 119, 180}, {255, 127, 14},  {44, 160, 44},   {214, 39, 40},  {148, 103, 189},
        {140, 86, 75},  {227, 119, 194}, {127, 127, 127}, {188, 189, 34}, {23, 190, 207}};
    const auto& c = kRgb[index % 10];
    return {c[2], c[1], c[0]};
}

std::string region_colour_css(std::size_t index) {
    const auto bgr = region_colour(index);
    return fmt::format("#{:02x}{:02x}{:02x}", bgr[2], bgr[1], bgr[0]);
}

void write_panel(const std::filesystem::path& panel,
                 const std::vector<std::filesystem::path>& parts, const std::vector<Plane>& planes,
                 const std::vector<QuicklookOptions>& options) {
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

RegionOverview region_overview(const std::vector<float>& s0, int width, int height,
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
            const float v = s0[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                               static_cast<std::size_t>(x)];
            grey.at<uchar>(y, x) =
                std::isfinite(v) ? cv::saturate_cast<uchar>(
                                       40.0 + 200.0 * std::clamp((v - lo) / (hi - lo), 0.0, 1.0))
                                 : uchar{128};
        }
    const cv::Size shown(std::max(1, static_cast<int>(std::lround(width * f))),
                         std::max(1, static_cast<int>(std::lround(height * f))));
    cv::resize(grey, grey, shown, 0, 0, f < 1.0 ? cv::INTER_AREA : cv::INTER_NEAREST);
    cv::cvtColor(grey, grey, cv::COLOR_GRAY2BGR);
    const int pad = 10;
    cv::Mat canvas(grey.rows + 2 * pad, grey.cols + 2 * pad, CV_8UC3, kWhite);
    grey.copyTo(canvas(cv::Rect(pad, pad, grey.cols, grey.rows)));
    RegionOverview overview;
    std::vector<double> label_em;
    std::vector<Box> targets;
    for (std::size_t r = 0; r < regions.size(); ++r) {
        const auto c = region_colour(r);
        const cv::Scalar colour(c[0], c[1], c[2]);
        std::vector<cv::Point> pts;
        for (const auto& p : regions[r].polygon)
            pts.emplace_back(pad + static_cast<int>(std::lround((p.x + 0.5) * f)),
                             pad + static_cast<int>(std::lround((p.y + 0.5) * f)));
        cv::polylines(canvas, std::vector<std::vector<cv::Point>>{pts}, true, colour, 2,
                      cv::LINE_AA);
        const cv::Rect bounds = cv::boundingRect(pts);
        targets.push_back({static_cast<double>(bounds.x), static_cast<double>(bounds.y),
                           static_cast<double>(bounds.x + bounds.width),
                           static_cast<double>(bounds.y + bounds.height)});
        label_em.push_back(label_width_em(regions[r].name));
    }
    constexpr double kLabelFontPx = 15.0, kLabelGapPx = 3.0;
    const LabelLayout layout =
        place_labels(label_em, targets, canvas.cols, canvas.rows, kLabelFontPx, kLabelGapPx);
    overview.font_px = layout.font_px;
    for (std::size_t r = 0; r < regions.size(); ++r)
        overview.labels.push_back({regions[r].name, layout.labels[r], region_colour_css(r)});
    std::vector<uchar> bytes;
    if (!cv::imencode(".png", canvas, bytes))
        fail("region overview: OpenCV could not encode the PNG");
    overview.png.assign(bytes.begin(), bytes.end());
    overview.width = canvas.cols;
    overview.height = canvas.rows;
    return overview;
}

}  // namespace tirpol::report::detail
