#include "tirpol/core/radiometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "tirpol/core/error.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/output_guard.h"

namespace tirpol {

double planck_radiance(double wavelength_um, double temperature_k) {
    if (temperature_k <= 0.0 || wavelength_um <= 0.0) return 0.0;
    const double x = kC2_um_K / (wavelength_um * temperature_k);
    const double l2 = wavelength_um * wavelength_um;
    return kC1L_W_um4_per_m2_sr / (l2 * l2 * wavelength_um * std::expm1(x));
}

double planck_radiance_dT(double wavelength_um, double temperature_k) {
    if (temperature_k <= 0.0 || wavelength_um <= 0.0) return 0.0;
    const double x = kC2_um_K / (wavelength_um * temperature_k);
    const double em1 = std::expm1(x);
    const double l2 = wavelength_um * wavelength_um;
    const double radiance = kC1L_W_um4_per_m2_sr / (l2 * l2 * wavelength_um * em1);
    // dL/dT = L · x/T · eˣ/(eˣ − 1)
    return radiance * x / temperature_k * (em1 + 1.0) / em1;
}

namespace {
constexpr double kMaxRelativeResponse = 1.05;
}  // namespace

SpectralResponse::SpectralResponse(std::vector<double> wavelength_um, std::vector<double> response)
    : m_wavelength_um(std::move(wavelength_um)), m_response(std::move(response)) {
    if (m_wavelength_um.size() != m_response.size() || m_wavelength_um.size() < 2)
        fail(
            "spectral response: need ≥ 2 (wavelength_um, response) pairs of equal length, got {} "
            "and {}",
            m_wavelength_um.size(), m_response.size());
    for (std::size_t i = 0; i < m_wavelength_um.size(); ++i) {
        if (!std::isfinite(m_wavelength_um[i]) || m_wavelength_um[i] <= 0.0)
            fail(
                "spectral response: wavelength_um[{}] = {} must be a positive number (micrometres)",
                i, m_wavelength_um[i]);
        if (!std::isfinite(m_response[i]) || m_response[i] < 0.0 ||
            m_response[i] > kMaxRelativeResponse)
            fail(
                "spectral response: response[{}] = {} at {} µm must lie in [0, 1] (a relative "
                "response, "
                "normalised to its peak; {} is tolerated for digitising noise; divide percentages "
                "by 100)",
                i, m_response[i], m_wavelength_um[i], kMaxRelativeResponse);
        if (i > 0 && m_wavelength_um[i] <= m_wavelength_um[i - 1])
            fail("spectral response: wavelengths must increase strictly, but {} follows {}",
                 m_wavelength_um[i], m_wavelength_um[i - 1]);
    }
}

namespace {
std::vector<std::string> split_csv_line(const std::string& line) {
    std::vector<std::string> out;
    std::string cell;
    std::istringstream in(line);
    while (std::getline(in, cell, ',')) {
        const auto b = cell.find_first_not_of(" \t\r");
        const auto e = cell.find_last_not_of(" \t\r");
        out.push_back(b == std::string::npos ? std::string() : cell.substr(b, e - b + 1));
    }
    return out;
}
}  // namespace

SpectralResponse SpectralResponse::load_csv(const std::filesystem::path& path) {
    check_input_file(path);
    std::ifstream in(path);
    if (!in) fail("{}: cannot open spectral response file", path.string());
    std::string line;
    int line_no = 0;
    long wl_col = -1, resp_col = -1;
    std::vector<double> wl, resp;
    while (std::getline(in, line)) {
        ++line_no;
        if (line.find_first_not_of(" \t\r") == std::string::npos ||
            line[line.find_first_not_of(" \t")] == '#')
            continue;
        auto cells = split_csv_line(line);
        if (wl_col < 0) {
            for (std::size_t i = 0; i < cells.size(); ++i) {
                if (cells[i] == "wavelength_um") wl_col = static_cast<long>(i);
                if (cells[i] == "response") resp_col = static_cast<long>(i);
            }
            if (wl_col < 0 || resp_col < 0)
                fail(
                    "{}:{}: expected a header with columns 'wavelength_um' and 'response', found "
                    "'{}'",
                    path.string(), line_no, line);
            continue;
        }
        auto parse = [&](long col, const char* name) {
            if (static_cast<std::size_t>(col) >= cells.size())
                fail("{}:{}: missing column '{}'", path.string(), line_no, name);
            const std::string& text = cells[static_cast<std::size_t>(col)];
            char* end = nullptr;
            const double v = std::strtod(text.c_str(), &end);
            if (text.empty() || end != text.c_str() + text.size())
                fail("{}:{}: column '{}': expected a number, found '{}'", path.string(), line_no,
                     name, text);
            return v;
        };
        if (wl.size() == limits::kMaxCsvRows)
            fail("{}:{}: more than {} data rows; tirpol reads spectral responses up to that size",
                 path.string(), line_no, limits::kMaxCsvRows);
        wl.push_back(parse(wl_col, "wavelength_um"));
        resp.push_back(parse(resp_col, "response"));
    }
    if (wl_col < 0)
        fail("{}: empty spectral response file (expected header 'wavelength_um,response')",
             path.string());
    try {
        return SpectralResponse(std::move(wl), std::move(resp));
    } catch (const Error& e) {
        fail("{}: {}", path.string(), e.what());
    }
}

double SpectralResponse::operator()(double wavelength_um) const {
    if (wavelength_um < m_wavelength_um.front() || wavelength_um > m_wavelength_um.back())
        return 0.0;
    const auto it = std::upper_bound(m_wavelength_um.begin(), m_wavelength_um.end(), wavelength_um);
    if (it == m_wavelength_um.end()) return m_response.back();
    const auto i = static_cast<std::size_t>(it - m_wavelength_um.begin());
    const double t =
        (wavelength_um - m_wavelength_um[i - 1]) / (m_wavelength_um[i] - m_wavelength_um[i - 1]);
    return m_response[i - 1] + t * (m_response[i] - m_response[i - 1]);
}

namespace {
// 8-point Gauss–Legendre nodes and weights on [−1, 1] (Abramowitz & Stegun, Table 25.4).
constexpr std::array<double, 4> kGlX = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                        0.9602898564975363};
constexpr std::array<double, 4> kGlW = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                        0.1012285362903763};
}  // namespace

Band::Band(double lo_um, double hi_um, std::optional<SpectralResponse> rsr, double max_panel_um)
    : m_lo_um(lo_um), m_hi_um(hi_um), m_rsr(std::move(rsr)) {
    if (!(lo_um >= limits::kMinWavelengthUm && hi_um <= limits::kMaxWavelengthUm && lo_um < hi_um))
        fail("band: expected {} ≤ lo < hi ≤ {} in micrometres, got [{}, {}]",
             limits::kMinWavelengthUm, limits::kMaxWavelengthUm, lo_um, hi_um);
    if (!(max_panel_um > 0.0 && std::isfinite(max_panel_um)))
        fail("band: quadrature panel width {} µm must be positive", max_panel_um);
    std::vector<double> breaks = {lo_um, hi_um};
    if (m_rsr)
        for (double w : m_rsr->wavelengths_um())
            if (w > lo_um && w < hi_um) breaks.push_back(w);
    // Bound the grid before building it: every panel holds 2·kGlX.size() nodes.
    const double panels_bound = (hi_um - lo_um) / max_panel_um + static_cast<double>(breaks.size());
    if (panels_bound * 2.0 * static_cast<double>(kGlX.size()) >
        static_cast<double>(limits::kMaxBandNodes))
        fail(
            "band [{}, {}] µm: {:.0f} quadrature panels of ≤ {} µm (plus the RSR's knots) exceed "
            "the {} spectral "
            "nodes tirpol integrates a band with; use a narrower band or a coarser RSR",
            lo_um, hi_um, panels_bound, max_panel_um, limits::kMaxBandNodes);
    std::sort(breaks.begin(), breaks.end());
    for (std::size_t p = 0; p + 1 < breaks.size(); ++p) {
        const double a = breaks[p], b = breaks[p + 1];
        const int panels = std::max(1, static_cast<int>(std::ceil((b - a) / max_panel_um)));
        const double h = (b - a) / panels;
        for (int q = 0; q < panels; ++q) {
            const double mid = a + (q + 0.5) * h, half = 0.5 * h;
            for (std::size_t g = 0; g < kGlX.size(); ++g)
                for (double sign : {-1.0, 1.0}) {
                    const double wl = mid + sign * half * kGlX[g];
                    const double weight = half * kGlW[g] * (m_rsr ? (*m_rsr)(wl) : 1.0);
                    if (weight > 0.0) m_nodes.push_back({wl, weight});
                }
        }
    }
    if (m_nodes.empty())
        fail("band [{}, {}] µm: the spectral response is zero everywhere in the band", lo_um,
             hi_um);
}

double Band::effective_width_um() const {
    double sum = 0.0;
    for (const auto& n : m_nodes) sum += n.weight_um;
    return sum;
}

double Band::radiance(double temperature_k) const {
    double sum = 0.0;
    for (const auto& n : m_nodes)
        sum += n.weight_um * planck_radiance(n.wavelength_um, temperature_k);
    return sum;
}

double Band::radiance_dT(double temperature_k) const {
    double sum = 0.0;
    for (const auto& n : m_nodes)
        sum += n.weight_um * planck_radiance_dT(n.wavelength_um, temperature_k);
    return sum;
}

double Band::brightness_temperature(double radiance_w_m2_sr) const {
    if (!std::isfinite(radiance_w_m2_sr) || radiance_w_m2_sr <= 0.0)
        return std::numeric_limits<double>::quiet_NaN();
    // Start from the monochromatic inversion at the band's centroid, then bracketed Newton.
    const double width = effective_width_um();
    double centroid = 0.0;
    for (const auto& n : m_nodes) centroid += n.weight_um * n.wavelength_um;
    centroid /= width;
    const double mean_l = radiance_w_m2_sr / width;
    double t =
        kC2_um_K / (centroid * std::log1p(kC1L_W_um4_per_m2_sr / (std::pow(centroid, 5) * mean_l)));
    double lo = 0.0, hi = std::numeric_limits<double>::infinity();
    for (int iter = 0; iter < 100; ++iter) {
        // Radiance and its derivative in one pass (one exp per node).
        double l = 0.0, d = 0.0;
        for (const auto& n : m_nodes) {
            const double x = kC2_um_K / (n.wavelength_um * t);
            const double em1 = std::expm1(x);
            const double w2 = n.wavelength_um * n.wavelength_um;
            const double ln =
                n.weight_um * kC1L_W_um4_per_m2_sr / (w2 * w2 * n.wavelength_um * em1);
            l += ln;
            d += ln * x / t * (em1 + 1.0) / em1;
        }
        const double f = l - radiance_w_m2_sr;
        if (f > 0.0)
            hi = std::min(hi, t);
        else
            lo = std::max(lo, t);
        double next = d > 0.0 ? t - f / d : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = std::isfinite(hi) ? 0.5 * (lo + hi) : 2.0 * t;
        if (std::abs(next - t) < 1e-7) return next;  // kelvin; Newton converges quadratically here
        t = next;
    }
    return t;
}

}  // namespace tirpol
