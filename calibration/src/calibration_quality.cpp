#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "fpa_state.h"
#include "tirpol/calibration/radiometric.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/quicklook.h"

namespace tirpol::calibration {

namespace {
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
// Scene temperature at which NEDT is conventionally quoted.
constexpr double kNedtQuoteK = 300.0;
// An FPA temperature this far outside the calibrated range is extrapolation worth a warning.
constexpr double kFpaMarginK = 0.5;

std::string kelvin_list(const std::vector<SetPointResidual>& s, double SetPointResidual::*field) {
    std::string out;
    for (const auto& p : s) out += fmt::format("{}{:+.0f}", out.empty() ? "" : ", ", p.*field);
    return out;
}
}  // namespace

CalibrationQuality assess_calibration(const RadiometricCalibration& cal,
                                      const std::vector<BlackbodyFrame>& frames) {
    CalibrationQuality q;
    const Band band = cal.band();
    const std::size_t n = cal.gain.size();
    std::size_t nedt_frame = 0;
    for (std::size_t j = 0; j < frames.size(); ++j) {
        const BlackbodyFrame& f = frames[j];
        if (f.counts.size() != n)
            fail("{}: {} pixels; the calibration has {}", f.source, f.counts.size(), n);
        const detail::FpaState state(cal, f.fpa_temperature_k, f.source);
        const double l = band.radiance(f.temperature_k);
        double sum = 0.0, sum2 = 0.0, responsivity = 0.0;
        std::size_t good = 0;
        for (std::size_t i = 0; i < n; ++i) {
            if (cal.bad[i] != 0.0f) continue;
            const double model = state.offset(i) + state.gain(i) * l + state.quadratic(i) * l * l;
            const double r = f.counts[i] - model;
            sum += r;
            sum2 += r * r;
            responsivity += state.gain(i) + 2.0 * state.quadratic(i) * l;
            ++good;
        }
        SetPointResidual s;
        s.temperature_k = f.temperature_k;
        s.fpa_temperature_k = f.fpa_temperature_k.value_or(kNan);
        s.pixels = good;
        if (good > 0) {
            const double counts_per_mk =
                responsivity / static_cast<double>(good) * band.radiance_dT(f.temperature_k) * 1e-3;
            s.mean_counts = sum / static_cast<double>(good);
            s.rms_counts = std::sqrt(sum2 / static_cast<double>(good));
            s.mean_mk = s.mean_counts / counts_per_mk;
            s.rms_mk = s.rms_counts / counts_per_mk;
            s.standard_error_mk = s.rms_mk / std::sqrt(static_cast<double>(good));
        }
        q.set_points.push_back(s);
        if (std::abs(f.temperature_k - kNedtQuoteK) <
            std::abs(frames[nedt_frame].temperature_k - kNedtQuoteK))
            nedt_frame = j;
    }

    // Structure: the pixel-mean residual of one set-point is far from zero beyond its own noise.
    std::map<long, int> distinct;
    for (const auto& f : frames) distinct[std::lround(f.temperature_k * 100.0)] = 1;
    if (cal.quadratic.empty() && distinct.size() >= 3) {
        const bool structured =
            std::any_of(q.set_points.begin(), q.set_points.end(), [](const SetPointResidual& s) {
                return std::abs(s.mean_mk) >
                       std::max(kStructuredResidualMk, 4.0 * s.standard_error_mk);
            });
        if (structured)
            q.warnings.push_back(
                fmt::format("the linear model leaves structured residuals (mean per set-point, mK: "
                            "{}); the camera's response is "
                            "curved — try --quadratic",
                            kelvin_list(q.set_points, &SetPointResidual::mean_mk)));
    }

    // NEDT per pixel: temporal σ of one frame ÷ responsivity (counts/K) at the set-point nearest
    // 300 K.
    q.nedt_k.assign(n, static_cast<float>(kNan));
    q.nedt_median_k = kNan;
    if (!frames.empty() && !frames[nedt_frame].counts_std.empty()) {
        const BlackbodyFrame& f = frames[nedt_frame];
        q.nedt_temperature_k = f.temperature_k;
        const detail::FpaState state(cal, f.fpa_temperature_k, f.source);
        const double l = band.radiance(f.temperature_k), dl_dt = band.radiance_dT(f.temperature_k);
        std::vector<float> good_values;
        for (std::size_t i = 0; i < n; ++i) {
            const double r = (state.gain(i) + 2.0 * state.quadratic(i) * l) * dl_dt;
            if (r > 0.0) q.nedt_k[i] = static_cast<float>(f.counts_std[i] / r);
            if (cal.bad[i] == 0.0f && std::isfinite(q.nedt_k[i]))
                good_values.push_back(q.nedt_k[i]);
        }
        if (!good_values.empty()) {
            std::nth_element(
                good_values.begin(),
                good_values.begin() + static_cast<std::ptrdiff_t>(good_values.size() / 2),
                good_values.end());
            q.nedt_median_k = good_values[good_values.size() / 2];
        }
    }
    return q;
}

double outside_calibrated_range_fraction(const RadiometricCalibration& cal,
                                         const std::vector<float>& radiance) {
    if (cal.radiances_w_m2_sr.empty()) return 0.0;
    const auto [lo, hi] =
        std::minmax_element(cal.radiances_w_m2_sr.begin(), cal.radiances_w_m2_sr.end());
    std::size_t outside = 0, good = 0;
    for (std::size_t i = 0; i < radiance.size() && i < cal.bad.size(); ++i) {
        if (cal.bad[i] != 0.0f || !std::isfinite(radiance[i])) continue;
        ++good;
        outside += radiance[i] < *lo || radiance[i] > *hi;
    }
    return good ? static_cast<double>(outside) / static_cast<double>(good) : 0.0;
}

std::optional<std::string> extrapolation_warning(const RadiometricCalibration& cal,
                                                 const std::vector<float>& radiance,
                                                 std::optional<double> fpa_temperature_k) {
    if (cal.radiances_w_m2_sr.empty()) return std::nullopt;
    const auto [lo, hi] =
        std::minmax_element(cal.radiances_w_m2_sr.begin(), cal.radiances_w_m2_sr.end());
    const auto [t_lo, t_hi] =
        std::minmax_element(cal.temperatures_k.begin(), cal.temperatures_k.end());
    std::size_t below = 0, above = 0, good = 0;
    for (std::size_t i = 0; i < radiance.size() && i < cal.bad.size(); ++i) {
        if (cal.bad[i] != 0.0f || !std::isfinite(radiance[i])) continue;
        ++good;
        if (radiance[i] < *lo) ++below;
        if (radiance[i] > *hi) ++above;
    }
    std::vector<std::string> parts;
    if (below + above > 0)
        parts.push_back(fmt::format(
            "{} of {} good pixels ({:.1f} %) are outside the calibrated blackbody range "
            "{:.2f}–{:.2f} K ({} below, {} above): their temperatures are extrapolated",
            below + above, good,
            100.0 * static_cast<double>(below + above) /
                static_cast<double>(std::max<std::size_t>(good, 1)),
            *t_lo, *t_hi, below, above));
    if (cal.fpa_degree() > 0 && fpa_temperature_k &&
        (*fpa_temperature_k < cal.fpa_min_k - kFpaMarginK ||
         *fpa_temperature_k > cal.fpa_max_k + kFpaMarginK))
        parts.push_back(
            fmt::format("the camera's FPA temperature {:.2f} K is outside the calibrated FPA range "
                        "{:.2f}–{:.2f} K: the drift model is extrapolated",
                        *fpa_temperature_k, cal.fpa_min_k, cal.fpa_max_k));
    if (parts.empty()) return std::nullopt;
    std::string out = parts[0];
    for (std::size_t k = 1; k < parts.size(); ++k) out += "; " + parts[k];
    return out;
}

std::string default_summary_dir(const std::string& calibration_path) {
    std::filesystem::path p(calibration_path);
    return (p.parent_path() / (p.stem().string() + ".summary")).string();
}

void write_calibration_summary(const std::filesystem::path& dir, const RadiometricCalibration& cal,
                               const CalibrationQuality& quality) {
    std::filesystem::create_directories(dir);
    Image maps(cal.width, cal.height);
    maps.set_channel("nedt_k", quality.nedt_k);
    maps.set_channel("bad", cal.bad);
    maps.attributes()["nedt_temperature_k"] = quality.nedt_temperature_k;
    maps.attributes()["bad_bits"] =
        std::string("1 dead, 2 hot, 4 noisy, 8 non-linear, 16 saturated");
    write_exr(dir / "maps.exr", maps);
    QuicklookOptions nedt;
    nedt.title = fmt::format("NEDT at {:.1f} K", quality.nedt_temperature_k);
    nedt.units = "K";
    write_quicklook(dir / "nedt.png", quality.nedt_k, cal.width, cal.height, nedt);
    QuicklookOptions bad;
    bad.title = "bad pixels (bits: 1 dead 2 hot 4 noisy 8 non-linear 16 saturated)";
    bad.vmin = 0.0;
    bad.vmax = 31.0;
    write_quicklook(dir / "bad_pixels.png", cal.bad, cal.width, cal.height, bad);
    PlotSeries mean{"mean residual (mK)", {}, {}, {31, 119, 180}, true, false};
    for (const auto& s : quality.set_points) {
        mean.x.push_back(s.temperature_k);
        mean.y.push_back(s.mean_mk);
    }
    // One point per set-point; sort so the line reads left to right.
    std::vector<std::size_t> order(mean.x.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return mean.x[a] < mean.x[b]; });
    PlotSeries sorted = mean;
    for (std::size_t k = 0; k < order.size(); ++k) {
        sorted.x[k] = mean.x[order[k]];
        sorted.y[k] = mean.y[order[k]];
    }
    sorted.dashed = cal.fpa_degree() > 0;  // several camera states: points, not a curve
    write_line_plot(dir / "residuals.png", {sorted},
                    {"Residual of the calibration per blackbody set-point",
                     "blackbody temperature (K)", "counts - model (mK)", std::nullopt, std::nullopt,
                     std::nullopt, std::nullopt, 900, 500, true, 0.0});

    std::string rows;
    for (const auto& s : quality.set_points)
        rows += fmt::format(
            "<tr><td>{:.2f}</td><td>{}</td><td>{:+.1f}</td><td>{:.1f}</td><td>{:+.3f}</"
            "td><td>{:.3f}</td></tr>\n",
            s.temperature_k,
            std::isfinite(s.fpa_temperature_k) ? fmt::format("{:.2f}", s.fpa_temperature_k) : "–",
            s.mean_mk, s.rms_mk, s.mean_counts, s.rms_counts);
    std::string warnings;
    for (const auto& w : quality.warnings) warnings += "<li>" + w + "</li>";
    for (const auto& w : cal.warnings) warnings += "<li>" + w + "</li>";
    const auto [t_lo, t_hi] =
        std::minmax_element(cal.temperatures_k.begin(), cal.temperatures_k.end());
    const std::string model = fmt::format(
        "{}{}", cal.quadratic.empty() ? "linear" : "quadratic",
        cal.fpa_degree() > 0
            ? fmt::format(", gain and offset of degree {} in FPA temperature about {:.2f} K "
                          "(calibrated over FPA {:.2f}–{:.2f} K)",
                          cal.fpa_degree(), cal.fpa_reference_k, cal.fpa_min_k, cal.fpa_max_k)
            : std::string(", one camera state"));
    const std::string html = fmt::format(
        R"(<!DOCTYPE html>
<html><head><meta charset="utf-8"><title>Radiometric calibration summary</title>
<style>body{{font-family:sans-serif;max-width:60em;margin:1em auto}} table{{border-collapse:collapse}}
td,th{{border:1px solid #ccc;padding:2px 8px;text-align:right}} img{{max-width:48%}} .warn{{color:#a40}}</style></head>
<body><h1>Radiometric calibration</h1>
<p>Camera {}; {}×{} pixels; created {}; band {:.2f}–{:.2f} µm.<br>Model: counts = o + g·L{}; {}.<br>
Calibrated blackbody range {:.2f}–{:.2f} K ({} frames): outside it temperatures are extrapolated.</p>
<h2>Warnings</h2><ul class="warn">{}</ul>
<h2>Residuals per set-point</h2>
<table><tr><th>blackbody K</th><th>FPA K</th><th>mean mK</th><th>RMS mK</th><th>mean counts</th><th>RMS counts</th></tr>
{}</table>
<p><img src="residuals.png" alt="residuals"></p>
<h2>NEDT and bad pixels</h2>
<p>Median NEDT {:.1f} mK at {:.1f} K (temporal σ of one frame ÷ responsivity). Bad pixels: {} (dead {}, hot {}, noisy {},
non-linear {}, saturated {}).</p>
<p><img src="nedt.png" alt="NEDT map"> <img src="bad_pixels.png" alt="bad-pixel map"></p>
</body></html>
)",
        cal.camera_id, cal.width, cal.height, cal.created_utc, cal.band_lo_um, cal.band_hi_um,
        cal.quadratic.empty() ? "" : " + q·L²", model, *t_lo, *t_hi, cal.temperatures_k.size(),
        warnings.empty() ? "<li>none</li>" : warnings, rows, 1000.0 * quality.nedt_median_k,
        quality.nedt_temperature_k, cal.bad_count(), cal.bad_count(kDead), cal.bad_count(kHot),
        cal.bad_count(kNoisy), cal.bad_count(kNonLinear), cal.bad_count(kSaturated));
    write_file_atomic(dir / "index.html", html);
}

}  // namespace tirpol::calibration
