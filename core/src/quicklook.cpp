#include "tirpol/core/quicklook.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"

namespace tirpol {

namespace {

void check_png_keyword(const std::filesystem::path& path, const std::string& keyword) {
    bool printable = !keyword.empty() && keyword.size() <= 79 && keyword.front() != ' ' &&
                     keyword.back() != ' ' && keyword.find("  ") == std::string::npos;
    for (const char c : keyword) printable = printable && c >= 0x20 && c <= 0x7e;
    if (!printable)
        fail(
            "{}: PNG text keyword '{}': expected 1–79 printable ASCII characters without "
            "leading, trailing or double spaces",
            path.string(), keyword);
}

/// One PNG chunk: length, type, data, CRC-32 of type and data (PNG specification §5.3).
std::string png_chunk(const char (&type)[5], const std::string& data) {
    std::string chunk;
    const auto put_u32 = [&chunk](std::uint32_t v) {
        for (int shift = 24; shift >= 0; shift -= 8)
            chunk.push_back(static_cast<char>((v >> shift) & 0xffu));
    };
    put_u32(static_cast<std::uint32_t>(data.size()));
    const std::string body = std::string(type, 4) + data;
    chunk += body;
    put_u32(static_cast<std::uint32_t>(
        crc32(0L, reinterpret_cast<const Bytef*>(body.data()), static_cast<uInt>(body.size()))));
    return chunk;
}

/// `png` with a text chunk per entry of `text` inserted after IHDR (the first chunk, 33 bytes in
/// with the signature), where every reader looks for them.
std::string with_text_chunks(const std::filesystem::path& path, const std::string& png,
                             const std::vector<std::pair<std::string, std::string>>& text) {
    constexpr std::size_t kAfterHeader = 8 + 4 + 4 + 13 + 4;
    if (png.size() < kAfterHeader || png.compare(12, 4, "IHDR") != 0)
        fail("{}: the encoded PNG does not start with its header chunk", path.string());
    std::string chunks;
    for (const auto& [keyword, value] : text) {
        check_png_keyword(path, keyword);
        const bool ascii =
            std::all_of(value.begin(), value.end(), [](char c) { return c > 0 && c < 0x7f; });
        if (ascii) {
            chunks += png_chunk("tEXt", keyword + '\0' + value);
        } else {
            // keyword, NUL, uncompressed (0, 0), empty language tag and translation, UTF-8 text.
            chunks += png_chunk("iTXt", keyword + std::string("\0\0\0\0\0", 5) + value);
        }
    }
    return png.substr(0, kAfterHeader) + chunks + png.substr(kAfterHeader);
}

// Moreland's "cool to warm" diverging map (K. Moreland, "Diverging Color Maps for Scientific
// Visualization", ISVC 2009), control points in sRGB.
cv::Vec3b coolwarm(double t) {
    static constexpr std::array<std::array<double, 4>, 5> kPoints = {{
        {0.00, 59, 76, 192},
        {0.25, 141, 176, 254},
        {0.50, 221, 221, 221},
        {0.75, 244, 154, 123},
        {1.00, 180, 4, 38},
    }};
    t = std::clamp(t, 0.0, 1.0);
    std::size_t i = 0;
    while (i + 2 < kPoints.size() && t > kPoints[i + 1][0]) ++i;
    const auto& a = kPoints[i];
    const auto& b = kPoints[i + 1];
    const double u = (t - a[0]) / (b[0] - a[0]);
    auto mix = [&](std::size_t c) { return cv::saturate_cast<uchar>(a[c] + u * (b[c] - a[c])); };
    return {mix(3), mix(2), mix(1)};  // BGR
}

cv::Mat lut_for(Colormap map) {
    cv::Mat gray(1, 256, CV_8UC1);
    for (int i = 0; i < 256; ++i) gray.at<uchar>(0, i) = static_cast<uchar>(i);
    cv::Mat lut(1, 256, CV_8UC3);
    if (map == Colormap::Diverging) {
        for (int i = 0; i < 256; ++i) lut.at<cv::Vec3b>(0, i) = coolwarm(i / 255.0);
    } else {
        cv::applyColorMap(gray, lut,
                          map == Colormap::Cyclic ? cv::COLORMAP_TWILIGHT : cv::COLORMAP_INFERNO);
    }
    return lut;
}

// OpenCV's Hershey fonts are ASCII only.
std::string ascii(const std::string& text) {
    std::string out;
    for (std::size_t i = 0; i < text.size();) {
        auto starts = [&](const char* s) { return text.compare(i, std::strlen(s), s) == 0; };
        if (starts("²")) {
            out += "^2";
            i += std::strlen("²");
        } else if (starts("³")) {
            out += "^3";
            i += std::strlen("³");
        } else if (starts("·")) {
            out += " ";
            i += std::strlen("·");
        } else if (starts("µ")) {
            out += "u";
            i += std::strlen("µ");
        } else if (starts("°")) {
            out += "deg";
            i += std::strlen("°");
        } else if (starts("ε")) {
            out += "e";
            i += std::strlen("ε");
        } else if (static_cast<unsigned char>(text[i]) < 128)
            out += text[i++];
        else
            ++i;
    }
    return out;
}

std::string tick_label(double v) {
    char buf[32];
    const double a = std::abs(v);
    if (a != 0.0 && (a < 1e-2 || a >= 1e4))
        std::snprintf(buf, sizeof buf, "%.2e", v);
    else
        std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
}

}  // namespace

Colormap default_colormap(const std::string& name) {
    if (name == "AoP") return Colormap::Cyclic;
    if (name == "S1" || name == "S2" || name == "S3" || name.rfind("diff", 0) == 0 ||
        name.rfind("delta", 0) == 0)
        return Colormap::Diverging;
    return Colormap::Sequential;
}

QuicklookOptions channel_quicklook_options(const std::string& channel_name,
                                           const std::string& radiance_units) {
    QuicklookOptions q;
    q.colormap = default_colormap(channel_name);
    q.title = channel_name;
    if (channel_name.size() == 2 && channel_name[0] == 'S') {
        q.units = radiance_units;
    } else if (channel_name == "DoLP") {
        q.units = "fraction";
        q.vmin = 0.0;
    } else if (channel_name == "AoP") {
        q.units = "deg";
        q.vmin = 0.0;
        q.vmax = 180.0;
    } else if (channel_name == "temperature_k") {
        q.units = "K";
    }
    return q;
}

std::pair<double, double> quicklook_range(const std::vector<float>& data,
                                          const QuicklookOptions& options) {
    std::vector<float> finite;
    finite.reserve(data.size());
    for (float v : data)
        if (std::isfinite(v))
            finite.push_back(options.colormap == Colormap::Diverging ? std::abs(v) : v);
    auto pct = [&](double p) {
        if (finite.empty()) return 0.0;
        auto k = static_cast<std::size_t>(p * static_cast<double>(finite.size() - 1));
        std::nth_element(finite.begin(), finite.begin() + static_cast<std::ptrdiff_t>(k),
                         finite.end());
        return static_cast<double>(finite[k]);
    };
    double lo, hi;
    if (options.colormap == Colormap::Diverging) {
        const double m = pct(0.99);
        lo = -m;
        hi = m;
    } else if (options.colormap == Colormap::Cyclic) {
        lo = 0.0;
        hi = 180.0;
    } else {
        lo = pct(0.01);
        hi = pct(0.99);
    }
    if (options.vmin) lo = *options.vmin;
    if (options.vmax) hi = *options.vmax;
    if (!(hi > lo)) {  // flat image: open a small window around its value
        const double c = lo, w = std::max(std::abs(c) * 1e-3, 1e-12);
        lo = c - w;
        hi = c + w;
    }
    return {lo, hi};
}

void write_quicklook(const std::filesystem::path& path, const std::vector<float>& data, int width,
                     int height, const QuicklookOptions& options) {
    if (data.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
        fail("{}: quicklook data has {} values for a {}×{} image", path.string(), data.size(),
             width, height);
    const auto [lo, hi] = quicklook_range(data, options);
    const cv::Mat lut = lut_for(options.colormap);

    int scale = options.scale;
    if (scale <= 0) scale = std::max(1, 320 / std::max(width, height));
    cv::Mat img(height, width, CV_8UC3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float v = data[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                                 static_cast<std::size_t>(x)];
            if (!std::isfinite(v)) {
                img.at<cv::Vec3b>(y, x) = {128, 128, 128};
                continue;
            }
            const int idx =
                static_cast<int>(std::lround(std::clamp((v - lo) / (hi - lo), 0.0, 1.0) * 255.0));
            img.at<cv::Vec3b>(y, x) = lut.at<cv::Vec3b>(0, idx);
        }
    if (scale > 1) cv::resize(img, img, {width * scale, height * scale}, 0, 0, cv::INTER_NEAREST);

    // Canvas: title on top, image, colorbar with three ticks on the right.
    const int pad = 10, title_h = 28, bar_w = 18, label_w = 90;
    const int canvas_w = img.cols + 2 * pad + bar_w + label_w,
              canvas_h = std::max(img.rows, 120) + title_h + 2 * pad;
    cv::Mat canvas(canvas_h, canvas_w, CV_8UC3, cv::Scalar(255, 255, 255));
    img.copyTo(canvas(cv::Rect(pad, title_h + pad, img.cols, img.rows)));
    const int bar_x = img.cols + 2 * pad, bar_y = title_h + pad, bar_h = img.rows;
    for (int y = 0; y < bar_h; ++y) {
        const int idx = static_cast<int>(
            std::lround(255.0 * (1.0 - static_cast<double>(y) / std::max(1, bar_h - 1))));
        cv::line(canvas, {bar_x, bar_y + y}, {bar_x + bar_w - 1, bar_y + y},
                 cv::Scalar(lut.at<cv::Vec3b>(0, idx)));
    }
    cv::rectangle(canvas, {bar_x, bar_y, bar_w, bar_h}, cv::Scalar(0, 0, 0));
    const auto font = cv::FONT_HERSHEY_SIMPLEX;
    for (int k = 0; k <= 2; ++k) {
        const double v = hi - (hi - lo) * k / 2.0;
        const int y = bar_y + (bar_h - 1) * k / 2;
        cv::line(canvas, {bar_x + bar_w, y}, {bar_x + bar_w + 4, y}, cv::Scalar(0, 0, 0));
        cv::putText(canvas, tick_label(v), {bar_x + bar_w + 6, y + 5}, font, 0.4,
                    cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    }
    std::string title = ascii(options.title);
    if (!options.units.empty()) title += " [" + ascii(options.units) + "]";
    cv::putText(canvas, title, {pad, title_h - 6}, font, 0.55, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);

    std::vector<uchar> encoded;
    bool ok = false;
    try {
        ok = cv::imencode(".png", canvas, encoded);
    } catch (const cv::Exception& e) {
        fail("{}: encoding PNG failed: {}", path.string(), e.what());
    }
    if (!ok) fail("{}: encoding PNG failed (OpenCV could not encode the image)", path.string());
    write_file_atomic(
        path, with_text_chunks(path, std::string(encoded.begin(), encoded.end()), options.text));
}

}  // namespace tirpol
