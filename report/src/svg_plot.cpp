#include "svg_plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

#include "html_report.h"

namespace tirpol::report::detail {

namespace {

// Plot geometry in SVG user units (the figure scales to its column in the page).
constexpr double kWidth = 520, kLeft = 78, kRight = 18, kTop = 36, kPlotHeight = 300, kBottom = 52;
constexpr double kPlotWidth = kWidth - kLeft - kRight;
constexpr const char* kFont = "font-family=\"system-ui, 'DejaVu Sans', sans-serif\"";

struct PlotFrame {
    double x_lo, x_hi, y_lo, y_hi;
    double x(double v) const { return kLeft + (v - x_lo) / (x_hi - x_lo) * kPlotWidth; }
    double y(double v) const {
        return kTop + kPlotHeight - (v - y_lo) / (y_hi - y_lo) * kPlotHeight;
    }
};

// Axes box, grid lines at the ticks, tick labels and axis titles. Labels sit outside the box in
// fixed margins sized for "−0.0025"-long numbers, so they neither overlap each other nor get
// clipped.
std::string axes(const PlotFrame& f, const std::string& title, const std::string& x_label,
                 const std::string& y_label) {
    std::string s =
        fmt::format("<text x=\"{}\" y=\"22\" font-size=\"15\" font-weight=\"600\">{}</text>\n",
                    kLeft, escape_markup(title));
    const auto xt = nice_ticks(f.x_lo, f.x_hi), yt = nice_ticks(f.y_lo, f.y_hi);
    const double xs = xt.size() > 1 ? xt[1] - xt[0] : f.x_hi - f.x_lo,
                 ys = yt.size() > 1 ? yt[1] - yt[0] : f.y_hi - f.y_lo;
    for (double v : xt)
        s += fmt::format(
            "<line x1=\"{0:.1f}\" x2=\"{0:.1f}\" y1=\"{1}\" y2=\"{2}\" stroke=\"#e3e6eb\"/>"
            "<text x=\"{0:.1f}\" y=\"{3}\" font-size=\"12\" text-anchor=\"middle\">{4}</text>\n",
            f.x(v), kTop, kTop + kPlotHeight, kTop + kPlotHeight + 16, tick_label(v, xs));
    for (double v : yt)
        s += fmt::format(
            "<line x1=\"{0}\" x2=\"{1}\" y1=\"{2:.1f}\" y2=\"{2:.1f}\" stroke=\"#e3e6eb\"/>"
            "<text x=\"{3}\" y=\"{2:.1f}\" dy=\"4\" font-size=\"12\" "
            "text-anchor=\"end\">{4}</text>\n",
            kLeft, kLeft + kPlotWidth, f.y(v), kLeft - 6, tick_label(v, ys));
    s += fmt::format(
        "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#5b6475\"/>\n",
        kLeft, kTop, kPlotWidth, kPlotHeight);
    s += fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"13\" text-anchor=\"middle\">{}</text>\n",
                     kLeft + kPlotWidth / 2, kTop + kPlotHeight + 38, escape_markup(x_label));
    s += fmt::format(
        "<text transform=\"translate(16 {}) rotate(-90)\" font-size=\"13\" "
        "text-anchor=\"middle\">{}</text>\n",
        kTop + kPlotHeight / 2, escape_markup(y_label));
    return s;
}

std::string open_svg(double height, const std::string& label) {
    // No xmlns: inline SVG in HTML needs none (the .svg files get it when written).
    return fmt::format(
        "<svg viewBox=\"0 0 {} {}\" role=\"img\" aria-label=\"{}\" "
        "{} fill=\"#1d2330\" style=\"width:100%;height:auto;max-width:{}px\">\n",
        kWidth, height, escape_markup(label), kFont, kWidth);
}

std::pair<double, double> padded(double lo, double hi) {
    if (!(hi > lo)) {
        const double w = std::max(std::abs(lo) * 1e-3, 1e-12);
        return {lo - w, hi + w};
    }
    const double m = 0.05 * (hi - lo);
    return {lo - m, hi + m};
}

}  // namespace

std::vector<double> nice_ticks(double lo, double hi, int target) {
    const double raw = (hi - lo) / std::max(1, target);
    const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
    double step = 10.0 * magnitude;
    for (double f : {1.0, 2.0, 2.5, 5.0})
        if (f * magnitude >= raw) {
            step = f * magnitude;
            break;
        }
    std::vector<double> ticks;
    const double tol = 1e-9 * (hi - lo);
    for (double k = std::ceil((lo - tol) / step); k * step <= hi + tol; k += 1.0)
        ticks.push_back(std::abs(k * step) < 1e-12 * step ? 0.0 : k * step);
    return ticks;
}

std::string tick_label(double value, double step) {
    if (std::abs(value) < 1e-9 * step) return "0";
    const double a = std::abs(step);
    if (a >= 1e5 || a < 1e-4) return fmt::format("{:.3g}", value);
    // Decimals the step needs (2.5 × 10^k needs one more than 10^k).
    int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(a) + 1e-9)));
    if (std::abs(a / std::pow(10.0, -decimals) - std::round(a / std::pow(10.0, -decimals))) > 1e-6)
        ++decimals;
    std::string text = fmt::format("{:.{}f}", value, decimals);
    if (value < 0) text = "−" + text.substr(1);  // a real minus sign
    return text;
}

std::string svg_scatter(const std::string& title, const std::string& units,
                        const std::vector<ScatterSeries>& series) {
    constexpr std::size_t kMaxPointsPerSeries = 1500;
    std::vector<float> all;
    for (const auto& s : series)
        for (std::size_t i = 0; i < s.measured.size(); ++i)
            if (std::isfinite(s.measured[i]) && std::isfinite(s.simulated[i])) {
                all.push_back(s.measured[i]);
                all.push_back(s.simulated[i]);
            }
    const auto range = percentile_range(all, 0.002, 0.998);
    const auto [lo, hi] = padded(range.first, range.second);
    const PlotFrame f{lo, hi, lo, hi};
    const std::string unit_suffix = units.empty() ? "" : " [" + units + "]";
    // Legend: one row per series under the plot, so long names never cover data or each other.
    const double legend_top = kTop + kPlotHeight + kBottom + 4;
    const double height = legend_top + 18.0 * static_cast<double>(series.size()) + 6;
    std::string s = open_svg(height, title + " scatter");
    s += axes(f, title, "measured" + unit_suffix, "simulated" + unit_suffix);
    s += fmt::format(
        "<defs><clipPath id=\"clip-{0}\"><rect x=\"{1}\" y=\"{2}\" width=\"{3}\" "
        "height=\"{4}\"/></clipPath>"
        "</defs>\n<g clip-path=\"url(#clip-{0})\">\n",
        std::hash<std::string>{}(title) % 1000000, kLeft, kTop, kPlotWidth, kPlotHeight);
    s += fmt::format(
        "<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"#5b6475\" "
        "stroke-dasharray=\"5 4\"/>\n",
        f.x(lo), f.y(lo), f.x(hi), f.y(hi));
    for (std::size_t r = 0; r < series.size(); ++r) {
        const auto& ser = series[r];
        s += fmt::format("<g fill=\"{}\" fill-opacity=\"0.55\">", region_colour_css(r));
        const std::size_t stride =
            std::max<std::size_t>(1, ser.measured.size() / kMaxPointsPerSeries);
        for (std::size_t i = 0; i < ser.measured.size(); i += stride)
            if (std::isfinite(ser.measured[i]) && std::isfinite(ser.simulated[i]))
                s += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"1.8\"/>",
                                 f.x(ser.measured[i]), f.y(ser.simulated[i]));
        s += "</g>\n";
    }
    s += "</g>\n";
    for (std::size_t r = 0; r < series.size(); ++r) {
        const double y = legend_top + 18.0 * static_cast<double>(r);
        s += fmt::format(
            "<rect x=\"{}\" y=\"{}\" width=\"11\" height=\"11\" rx=\"2\" fill=\"{}\"/><text "
            "x=\"{}\" y=\"{}\" "
            "font-size=\"13\">{}</text>\n",
            kLeft, y, region_colour_css(r), kLeft + 17, y + 10, escape_markup(series[r].name));
    }
    return s + "</svg>\n";
}

std::string svg_histogram(const std::string& title, const std::string& x_label,
                          const std::vector<float>& values, double lo, double hi,
                          const std::vector<double>& markers, double gaussian_mean,
                          double gaussian_sigma) {
    constexpr int kBins = 60;
    std::vector<double> density(kBins, 0.0);
    std::size_t n = 0;
    const double width = (hi - lo) / kBins;
    for (float v : values) {
        if (!std::isfinite(v)) continue;
        ++n;
        const int b = static_cast<int>(std::floor((v - lo) / width));
        if (b >= 0 && b < kBins) density[static_cast<std::size_t>(b)] += 1.0;
    }
    for (auto& d : density) d = n ? d / (static_cast<double>(n) * width) : 0.0;
    auto gauss = [&](double x) {
        return std::exp(-0.5 * std::pow((x - gaussian_mean) / gaussian_sigma, 2)) /
               (gaussian_sigma * std::sqrt(2.0 * std::numbers::pi));
    };
    double top = *std::max_element(density.begin(), density.end());
    if (gaussian_sigma > 0.0) top = std::max(top, gauss(gaussian_mean));
    const PlotFrame f{lo, hi, 0.0, top > 0.0 ? 1.08 * top : 1.0};
    std::string s = open_svg(kTop + kPlotHeight + kBottom, title + " histogram");
    s += axes(f, title, x_label, "density");
    s += "<g fill=\"#4e79a7\" fill-opacity=\"0.75\">";
    for (int b = 0; b < kBins; ++b) {
        const double x0 = f.x(lo + b * width), x1 = f.x(lo + (b + 1) * width),
                     y = f.y(density[static_cast<std::size_t>(b)]);
        s += fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\"/>", x0,
                         y, std::max(0.0, x1 - x0 - 0.5), kTop + kPlotHeight - y);
    }
    s += "</g>\n";
    for (double m : markers)
        if (m >= lo && m <= hi)
            s += fmt::format(
                "<line x1=\"{0:.1f}\" x2=\"{0:.1f}\" y1=\"{1}\" y2=\"{2}\" stroke=\"#8a919e\" "
                "stroke-width=\"1.5\"/>\n",
                f.x(m), kTop, kTop + kPlotHeight);
    if (gaussian_sigma > 0.0) {
        std::string points;
        for (int k = 0; k <= 200; ++k) {
            const double x = lo + (hi - lo) * k / 200.0;
            points += fmt::format("{:.1f},{:.1f} ", f.x(x), f.y(gauss(x)));
        }
        s += fmt::format(
            "<polyline points=\"{}\" fill=\"none\" stroke=\"#d62728\" stroke-width=\"2\"/>\n",
            points);
    }
    return s + "</svg>\n";
}

std::string svg_region_overview(const RegionOverview& overview) {
    std::string svg = fmt::format(
        "<svg class=\"region-overview\" viewBox=\"0 0 {0} {1}\" width=\"{0}\" height=\"{1}\" "
        "role=\"img\"><image width=\"{0}\" height=\"{1}\" "
        "href=\"data:image/png;base64,{2}\"/>",
        overview.width, overview.height, base64_encode(overview.png));
    for (const auto& label : overview.labels)
        if (label.placed.leader)
            svg += fmt::format(
                "<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"{}\" "
                "stroke-width=\"1.5\"/>",
                label.placed.leader_x0, label.placed.leader_y0, label.placed.leader_x1,
                label.placed.leader_y1, label.colour_css);
    // The text is drawn at exactly the box's width (textLength), centred on its middle line, so
    // the box the layout kept free is the one the browser fills.
    for (const auto& label : overview.labels) {
        const Box& b = label.placed.box;
        svg += fmt::format(
            "<text class=\"region-label\" x=\"{:.1f}\" y=\"{:.1f}\" textLength=\"{:.1f}\" "
            "lengthAdjust=\"spacingAndGlyphs\" dominant-baseline=\"central\" {} "
            "font-size=\"{:.1f}\" fill=\"{}\" stroke=\"white\" stroke-width=\"3.5\" "
            "paint-order=\"stroke\">{}</text>",
            b.x0, 0.5 * (b.y0 + b.y1), b.width(), kFont, overview.font_px, label.colour_css,
            escape_markup(label.name));
    }
    return svg + "</svg>";
}

}  // namespace tirpol::report::detail
