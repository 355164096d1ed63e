#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/quicklook.h"
#include "tirpol/fitting/fit_run.h"

namespace tirpol::fitting {

namespace {

constexpr int kWidth = 1000, kPanelHeight = 380, kTop = 50;
constexpr int kLeft = 95, kRight = 30, kPanelGap = 40;
const cv::Scalar kBlack(0, 0, 0), kGrey(200, 200, 200);
// Colour-blind-safe palette (Okabe & Ito 2008), BGR.
const cv::Scalar kPalette[] = {
    {178, 114, 0}, {0, 94, 213}, {115, 158, 0}, {167, 121, 204}, {66, 228, 240}};
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

struct AxisRange {
    double lo, hi;
};

struct Panel {
    cv::Rect box;
    AxisRange x, y;
    int px(double v) const {
        return box.x + static_cast<int>(std::lround((v - x.lo) / (x.hi - x.lo) * box.width));
    }
    int py(double v) const {
        return box.y + box.height -
               static_cast<int>(std::lround((v - y.lo) / (y.hi - y.lo) * box.height));
    }
};

void draw_axes(cv::Mat& img, const Panel& p, const std::string& y_label, bool x_label) {
    cv::rectangle(img, p.box, kBlack, 1);
    for (double t = 0.0; t <= 90.0 + 1e-9; t += 10.0) {
        const int x = p.px(t);
        cv::line(img, {x, p.box.y + p.box.height}, {x, p.box.y + p.box.height - 6}, kBlack, 1);
        cv::line(img, {x, p.box.y + 1}, {x, p.box.y + p.box.height - 7}, kGrey, 1);
        const std::string s = fmt::format("{:g}", t);
        cv::putText(img, s, {x - 5 * static_cast<int>(s.size()), p.box.y + p.box.height + 20},
                    kFont, 0.45, kBlack, 1, cv::LINE_AA);
    }
    for (double t : nice_ticks(p.y.lo, p.y.hi, 6)) {
        if (t < p.y.lo || t > p.y.hi) continue;
        const int y = p.py(t);
        cv::line(img, {p.box.x, y}, {p.box.x + 6, y}, kBlack, 1);
        cv::line(img, {p.box.x + 7, y}, {p.box.x + p.box.width - 1, y}, kGrey, 1);
        const std::string s = fmt::format("{:.3g}", std::abs(t) < 1e-12 ? 0.0 : t);
        cv::putText(img, s, {p.box.x - 10 - 9 * static_cast<int>(s.size()), y + 5}, kFont, 0.45,
                    kBlack, 1, cv::LINE_AA);
    }
    cv::putText(img, y_label, {8, p.box.y - 10}, kFont, 0.55, kBlack, 1, cv::LINE_AA);
    if (x_label)
        cv::putText(img, "view angle from the surface normal (deg)",
                    {p.box.x + p.box.width / 2 - 170, p.box.y + p.box.height + 42}, kFont, 0.55,
                    kBlack, 1, cv::LINE_AA);
}

}  // namespace

void write_fit_plot(const std::filesystem::path& png,
                    const std::vector<EmissivityDataset>& datasets,
                    const MicrofacetFitResult& result, const std::string& title,
                    const QuadratureOptions& quadrature) {
    // Model curves per band.
    std::vector<double> angles;
    for (double a = 0.0; a <= 89.5 + 1e-9; a += 0.5) angles.push_back(a);
    std::vector<std::vector<std::pair<double, double>>> curves(result.wavelengths_um.size());
    for (double a : angles) {
        const EmissivityQuadrature q(deg_to_rad(a), quadrature);
        for (std::size_t b = 0; b < curves.size(); ++b)
            curves[b].push_back(q.emissivity(result.model_parameters(b)));
    }

    // Ranges covering data (with 2σ bars) and curves.
    AxisRange y0{1e9, -1e9}, y1{1e9, -1e9};
    auto grow = [](AxisRange& a, double v) {
        a.lo = std::min(a.lo, v);
        a.hi = std::max(a.hi, v);
    };
    for (const auto& d : datasets)
        for (const auto& s : d.samples) {
            grow(y0, s.eps_s0 - 2 * s.eps_s0_std);
            grow(y0, s.eps_s0 + 2 * s.eps_s0_std);
            grow(y1, s.eps_s1 - 2 * s.eps_s1_std);
            grow(y1, s.eps_s1 + 2 * s.eps_s1_std);
        }
    for (const auto& c : curves)
        for (const auto& [s0, s1] : c) {
            grow(y0, s0);
            grow(y1, s1);
        }
    grow(y1, 0.0);
    for (AxisRange* a : {&y0, &y1}) {
        const double pad = 0.06 * std::max(a->hi - a->lo, 1e-3);
        a->lo -= pad;
        a->hi += pad;
    }

    const int height = kTop + 2 * kPanelHeight + kPanelGap + 70;
    cv::Mat img(height, kWidth, CV_8UC3, cv::Scalar(255, 255, 255));
    cv::putText(img, title, {kLeft, 30}, kFont, 0.7, kBlack, 2, cv::LINE_AA);
    const int w = kWidth - kLeft - kRight;
    const Panel top{{kLeft, kTop + 10, w, kPanelHeight - 30}, {0, 90}, y0};
    const Panel bottom{{kLeft, kTop + kPanelHeight + kPanelGap, w, kPanelHeight - 30}, {0, 90}, y1};
    draw_axes(img, top, "eps_S0", false);
    draw_axes(img, bottom, "eps_S1", true);

    for (std::size_t b = 0; b < curves.size(); ++b) {
        const cv::Scalar colour = kPalette[b % std::size(kPalette)];
        std::vector<cv::Point> l0, l1;
        for (std::size_t i = 0; i < angles.size(); ++i) {
            l0.emplace_back(top.px(angles[i]), top.py(curves[b][i].first));
            l1.emplace_back(bottom.px(angles[i]), bottom.py(curves[b][i].second));
        }
        cv::polylines(img, l0, false, colour, 2, cv::LINE_AA);
        cv::polylines(img, l1, false, colour, 2, cv::LINE_AA);
    }
    for (const auto& d : datasets) {
        const auto band = static_cast<std::size_t>(
            std::find(result.wavelengths_um.begin(), result.wavelengths_um.end(), d.wavelength_um) -
            result.wavelengths_um.begin());
        const cv::Scalar colour = kPalette[band % std::size(kPalette)];
        for (const auto& s : d.samples) {
            for (const auto& [panel, v, sg] : {std::tuple{&top, s.eps_s0, s.eps_s0_std},
                                               std::tuple{&bottom, s.eps_s1, s.eps_s1_std}}) {
                const int x = panel->px(s.angle_deg);
                cv::line(img, {x, panel->py(v - 2 * sg)}, {x, panel->py(v + 2 * sg)}, kBlack, 1,
                         cv::LINE_AA);
                cv::line(img, {x - 4, panel->py(v - 2 * sg)}, {x + 4, panel->py(v - 2 * sg)},
                         kBlack, 1);
                cv::line(img, {x - 4, panel->py(v + 2 * sg)}, {x + 4, panel->py(v + 2 * sg)},
                         kBlack, 1);
                cv::circle(img, {x, panel->py(v)}, 4, colour, cv::FILLED, cv::LINE_AA);
                cv::circle(img, {x, panel->py(v)}, 4, kBlack, 1, cv::LINE_AA);
            }
        }
    }

    // Legend (top panel, lower left: ε_S0 falls towards grazing, so that corner is usually empty).
    int ly = top.box.y + top.box.height - 22 * static_cast<int>(curves.size() + 1) - 4;
    const int lx = top.box.x + 15;
    cv::circle(img, {lx + 12, ly}, 4, kBlack, 1, cv::LINE_AA);
    cv::line(img, {lx + 12, ly - 9}, {lx + 12, ly + 9}, kBlack, 1);
    cv::putText(img, "measured, 2-sigma error bars", {lx + 35, ly + 5}, kFont, 0.45, kBlack, 1,
                cv::LINE_AA);
    for (std::size_t b = 0; b < curves.size(); ++b) {
        ly += 22;
        cv::line(img, {lx, ly}, {lx + 25, ly}, kPalette[b % std::size(kPalette)], 2, cv::LINE_AA);
        cv::putText(
            img,
            fmt::format(
                "micro-facet fit{} (chi2/dof = {:.2f})",
                curves.size() > 1 ? fmt::format(" at {:g} um", result.wavelengths_um[b]) : "",
                result.reduced_chi2),
            {lx + 35, ly + 5}, kFont, 0.45, kBlack, 1, cv::LINE_AA);
    }

    std::vector<unsigned char> buffer;
    if (!cv::imencode(".png", img, buffer)) fail("{}: PNG encoding failed", png.string());
    write_file_atomic(
        png, std::string_view(reinterpret_cast<const char*>(buffer.data()), buffer.size()));
}

}  // namespace tirpol::fitting
