#include "tirpol/calibration/radiometric.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "fpa_state.h"
#include "tirpol/core/error.h"
#include "tirpol/core/utc_time.h"
#include "validate.h"

namespace tirpol::calibration {

Band RadiometricCalibration::band() const {
    std::optional<SpectralResponse> rsr;
    if (!rsr_wavelength_um.empty()) rsr = SpectralResponse(rsr_wavelength_um, rsr_response);
    return Band(band_lo_um, band_hi_um, rsr);
}

std::size_t RadiometricCalibration::bad_count(std::uint32_t bits) const {
    return static_cast<std::size_t>(std::count_if(bad.begin(), bad.end(), [bits](float b) {
        return (static_cast<std::uint32_t>(b) & bits) != 0;
    }));
}

namespace {
void validate_frames(const std::vector<BlackbodyFrame>& frames, int width, int height,
                     std::size_t n_params, int fpa_degree) {
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    std::vector<double> temps;
    for (const auto& f : frames) {
        if (!(f.temperature_k > 0.0) || !std::isfinite(f.temperature_k))
            fail("{}: blackbody temperature {} K; expected a finite temperature above 0 K",
                 f.source, f.temperature_k);
        detail::check_plane(f.counts, n, f.source + " (counts)", width, height);
        if (!f.counts_std.empty())
            detail::check_plane(f.counts_std, n, f.source + " (counts_std)", width, height);
        if (f.frames < 1) fail("{}: frames = {}; expected at least 1", f.source, f.frames);
        if (fpa_degree > 0 && (!f.fpa_temperature_k || !(*f.fpa_temperature_k > 0.0) ||
                               !std::isfinite(*f.fpa_temperature_k)))
            fail(
                "{}: an FPA-temperature-dependent calibration (degree {}) needs each frame's FPA "
                "temperature; expected "
                "fpa_temperature_k in kelvin, got {}",
                f.source, fpa_degree,
                f.fpa_temperature_k ? fmt::format("{}", *f.fpa_temperature_k) : "none");
        if (std::none_of(temps.begin(), temps.end(),
                         [&](double t) { return std::abs(t - f.temperature_k) < 1e-3; }))
            temps.push_back(f.temperature_k);
    }
    if (temps.size() < n_params)
        fail(
            "blackbody set has {} distinct temperature(s) ({} frame(s)); the {} model needs at "
            "least {}",
            temps.size(), frames.size(), n_params == 3 ? "quadratic" : "linear", n_params);
}

double robust_floor(const RobustStats& s, double floor) { return std::max(s.sigma, floor); }

// Above this spread of camera temperatures a single-state calibration of a typical uncooled camera
// (tens of counts per kelvin of FPA drift) errs by tenths of a kelvin: worth a warning.
constexpr double kFpaSpanWarningK = 1.0;
}  // namespace

namespace {
/// A warmer blackbody gives more counts: a gain ≤ 0 (or not finite) for most pixels means the
/// records' temperatures do not belong to their frames (swapped, mistyped), and every NEDT would be
/// undefined. Names the records that break the order (spatial median counts against temperature).
void check_physical_gain(const std::vector<BlackbodyFrame>& frames,
                         const std::vector<float>& gain) {
    std::size_t unphysical = 0;
    for (float g : gain)
        if (!(g > 0.0f) || !std::isfinite(g)) ++unphysical;
    if (2 * unphysical <= gain.size()) return;
    std::vector<double> median(frames.size());
    for (std::size_t j = 0; j < frames.size(); ++j) {
        std::vector<float> counts;
        for (float c : frames[j].counts)
            if (std::isfinite(c)) counts.push_back(c);
        median[j] = robust_stats(counts).median;
    }
    std::vector<std::string> inversions;
    for (std::size_t i = 0; i < frames.size(); ++i)
        for (std::size_t j = 0; j < frames.size(); ++j)
            if (frames[i].temperature_k < frames[j].temperature_k && median[i] >= median[j])
                inversions.push_back(fmt::format(
                    "{} at {:g} K reads a median of {:.1f} counts, not less than {} at {:g} K "
                    "({:.1f} counts)",
                    frames[i].source, frames[i].temperature_k, median[i], frames[j].source,
                    frames[j].temperature_k, median[j]));
    std::string records;
    if (inversions.empty()) {
        for (std::size_t j = 0; j < frames.size(); ++j)
            records += fmt::format("{}{} at {:g} K ({:.1f} counts)", j ? ", " : "",
                                   frames[j].source, frames[j].temperature_k, median[j]);
    } else {
        const std::size_t shown = std::min<std::size_t>(inversions.size(), 3);
        for (std::size_t k = 0; k < shown; ++k) records += (k ? "; " : "") + inversions[k];
        if (inversions.size() > shown)
            records += fmt::format("; and {} more such pair(s)", inversions.size() - shown);
    }
    fail(
        "radiometric calibration: the fit gives a gain ≤ 0 or not finite (counts falling as the "
        "blackbody warms, "
        "NEDT undefined) for {} of {} pixels: the blackbody records do not agree with their "
        "temperatures: {}. Are "
        "temperatures swapped or mistyped in the session manifest? No calibration written",
        unphysical, gain.size(), records);
}
}  // namespace

RadiometricCalibration fit_radiometric(const std::vector<BlackbodyFrame>& frames, int width,
                                       int height, const Band& band,
                                       const RadiometricOptions& options) {
    if (options.fpa_degree < 0 || options.fpa_degree > 2)
        fail("FPA-temperature degree {}; expected 0 (one camera state), 1 or 2",
             options.fpa_degree);
    const std::size_t d = static_cast<std::size_t>(options.fpa_degree);
    validate_frames(frames, width, height, options.quadratic ? 3 : 2, options.fpa_degree);
    // Columns: 1, ΔT..ΔT^d (offset), L, L·ΔT..L·ΔT^d (gain), [L²].
    const std::size_t p = 2 * (d + 1) + (options.quadratic ? 1 : 0);
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    const std::size_t k = frames.size();

    RadiometricCalibration cal;
    cal.width = width;
    cal.height = height;
    cal.band_lo_um = band.lo_um();
    cal.band_hi_um = band.hi_um();
    if (band.rsr()) {
        cal.rsr_wavelength_um = band.rsr()->wavelengths_um();
        cal.rsr_response = band.rsr()->responses();
    }
    cal.created_utc = utc_now_iso8601();
    cal.bad.assign(n, 0.0f);

    // Saturation: a few saturated pixels are a bad-pixel class; a frame full of them means the
    // blackbody was too hot for the integration time, and the calibration would be wrong.
    if (options.saturation_counts) {
        for (const auto& f : frames) {
            std::size_t saturated = 0;
            for (std::size_t i = 0; i < n; ++i)
                if (f.counts[i] >= *options.saturation_counts) {
                    ++saturated;
                    cal.bad[i] =
                        static_cast<float>(static_cast<std::uint32_t>(cal.bad[i]) | kSaturated);
                }
            if (static_cast<double>(saturated) >
                options.max_saturated_fraction * static_cast<double>(n))
                fail(
                    "{}: {} of {} pixels are saturated (counts ≥ {}) at T = {} K; expected at most "
                    "{:.3g}% — lower "
                    "the blackbody temperature or the integration time",
                    f.source, saturated, n, *options.saturation_counts, f.temperature_k,
                    100.0 * options.max_saturated_fraction);
        }
    }

    if (d > 0) {
        double sum = 0.0;
        cal.fpa_min_k = cal.fpa_max_k = *frames[0].fpa_temperature_k;
        for (const auto& f : frames) {
            sum += *f.fpa_temperature_k;
            cal.fpa_min_k = std::min(cal.fpa_min_k, *f.fpa_temperature_k);
            cal.fpa_max_k = std::max(cal.fpa_max_k, *f.fpa_temperature_k);
            cal.fpa_temperatures_k.push_back(*f.fpa_temperature_k);
        }
        // Centring ΔT on the frames' mean keeps the design well conditioned.
        cal.fpa_reference_k = sum / static_cast<double>(k);
    }
    Eigen::MatrixXd a(k, p);
    for (std::size_t j = 0; j < k; ++j) {
        const auto row = static_cast<Eigen::Index>(j);
        const double l = band.radiance(frames[j].temperature_k);
        cal.temperatures_k.push_back(frames[j].temperature_k);
        cal.radiances_w_m2_sr.push_back(l);
        const double dt = d > 0 ? *frames[j].fpa_temperature_k - cal.fpa_reference_k : 0.0;
        double power = 1.0;
        for (std::size_t e = 0; e <= d; ++e, power *= dt) {
            a(row, static_cast<Eigen::Index>(e)) = power;
            a(row, static_cast<Eigen::Index>(d + 1 + e)) = l * power;
        }
        if (options.quadratic) a(row, static_cast<Eigen::Index>(p - 1)) = l * l;
    }
    if (d > 0) {
        // Columns of ΔT span kelvin, of L·ΔT² thousands: judge the rank on unit-norm columns.
        const Eigen::MatrixXd scaled =
            a * a.colwise().norm().cwiseMax(1e-300).cwiseInverse().asDiagonal();
        Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(scaled);
        qr.setThreshold(1e-9);
        if (static_cast<std::size_t>(qr.rank()) < p)
            fail(
                "the {} blackbody frame(s) do not determine an FPA-temperature model of degree {}: "
                "it needs blackbody "
                "frames at ≥ {} temperatures at each of ≥ {} distinct FPA temperatures (the "
                "frames' FPA temperatures "
                "span {:.2f}–{:.2f} K)",
                k, d, options.quadratic ? 3 : 2, d + 1, cal.fpa_min_k, cal.fpa_max_k);
    }
    // The same least-squares projector serves every pixel: coefficients = P·counts.
    const Eigen::MatrixXd projector = a.completeOrthogonalDecomposition().pseudoInverse();

    cal.offset.resize(n);
    cal.gain.resize(n);
    if (options.quadratic) cal.quadratic.resize(n);
    cal.offset_fpa.assign(d, std::vector<float>(n));
    cal.gain_fpa.assign(d, std::vector<float>(n));
    cal.residual_rms.resize(n);
    cal.fit_quality.resize(n);
    std::vector<float> temporal_noise(n, std::numeric_limits<float>::quiet_NaN());
    const bool have_std = std::all_of(frames.begin(), frames.end(),
                                      [](const auto& f) { return !f.counts_std.empty(); });
    const double dof = static_cast<double>(k) - static_cast<double>(p);

    Eigen::VectorXd c(k);
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j = 0; j < k; ++j) c[static_cast<Eigen::Index>(j)] = frames[j].counts[i];
        const Eigen::VectorXd coef = projector * c;
        const Eigen::VectorXd r = c - a * coef;
        cal.offset[i] = static_cast<float>(coef[0]);
        cal.gain[i] = static_cast<float>(coef[static_cast<Eigen::Index>(d + 1)]);
        for (std::size_t e = 1; e <= d; ++e) {
            cal.offset_fpa[e - 1][i] = static_cast<float>(coef[static_cast<Eigen::Index>(e)]);
            cal.gain_fpa[e - 1][i] = static_cast<float>(coef[static_cast<Eigen::Index>(d + 1 + e)]);
        }
        if (options.quadratic)
            cal.quadratic[i] = static_cast<float>(coef[static_cast<Eigen::Index>(p - 1)]);
        cal.residual_rms[i] =
            static_cast<float>(std::sqrt(r.squaredNorm() / static_cast<double>(k)));
        float quality = std::numeric_limits<float>::quiet_NaN();
        if (have_std) {
            double var_mean = 0.0, var_frame = 0.0;
            for (const auto& f : frames) {
                const double s = f.counts_std[i];
                var_mean += s * s / f.frames;
                var_frame += s * s;
            }
            temporal_noise[i] = static_cast<float>(std::sqrt(var_frame / static_cast<double>(k)));
            if (dof > 0.0 && var_mean > 0.0)
                quality = static_cast<float>(std::sqrt(r.squaredNorm() / dof) /
                                             std::sqrt(var_mean / static_cast<double>(k)));
        }
        cal.fit_quality[i] = quality;
    }

    check_physical_gain(frames, cal.gain);

    // Bad-pixel detection on robust statistics (median, 1.4826·MAD) of the good pixels' maps.
    const BadPixelThresholds& th = options.thresholds;
    const RobustStats gain_stats = robust_stats(cal.gain);
    const RobustStats offset_stats = robust_stats(cal.offset);
    const RobustStats residual_stats = robust_stats(cal.residual_rms);
    const RobustStats noise_stats = robust_stats(temporal_noise);
    const double span =
        std::abs(gain_stats.median) *
        (*std::max_element(cal.radiances_w_m2_sr.begin(), cal.radiances_w_m2_sr.end()) -
         *std::min_element(cal.radiances_w_m2_sr.begin(), cal.radiances_w_m2_sr.end()));
    // Floors keep noiseless (synthetic) data from flagging round-off: 1e-4 of the counts span.
    const double offset_sigma = robust_floor(offset_stats, 1e-4 * span);
    const double residual_sigma = robust_floor(residual_stats, 1e-4 * span);
    for (std::size_t i = 0; i < n; ++i) {
        std::uint32_t bits = static_cast<std::uint32_t>(cal.bad[i]);
        if (!(cal.gain[i] >= th.dead_gain_fraction * gain_stats.median)) bits |= kDead;
        if (cal.offset[i] > offset_stats.median + th.hot_sigma * offset_sigma) bits |= kHot;
        if (have_std && temporal_noise[i] > th.noisy_factor * noise_stats.median) bits |= kNoisy;
        // A large residual that the pixel's own temporal noise explains (fit quality ≲ 3) is a
        // noisy pixel, not a non-linear one.
        const bool explained_by_noise =
            std::isfinite(cal.fit_quality[i]) && cal.fit_quality[i] < 3.0f;
        if (dof > 0.0 && !explained_by_noise &&
            cal.residual_rms[i] > residual_stats.median + th.nonlinear_sigma * residual_sigma)
            bits |= kNonLinear;
        cal.bad[i] = static_cast<float>(bits);
    }
    if (d == 0) {
        // A single-state fit over frames at different camera temperatures folds the drift into the
        // fit.
        double lo = 0.0, hi = 0.0;
        bool any = false;
        for (const auto& f : frames)
            if (f.fpa_temperature_k) {
                lo = any ? std::min(lo, *f.fpa_temperature_k) : *f.fpa_temperature_k;
                hi = any ? std::max(hi, *f.fpa_temperature_k) : *f.fpa_temperature_k;
                any = true;
            }
        if (any && hi - lo > kFpaSpanWarningK)
            cal.warnings.push_back(
                fmt::format("the blackbody frames span {:.2f}–{:.2f} K of FPA temperature but the "
                            "calibration is for one camera "
                            "state; fit the FPA dependence (--fpa-degree 1)",
                            lo, hi));
    }
    return cal;
}

std::vector<float> counts_to_radiance(const RadiometricCalibration& cal,
                                      const std::vector<float>& counts,
                                      std::optional<double> fpa_temperature_k) {
    const std::size_t n = cal.gain.size();
    detail::check_plane(counts, n, "counts → radiance input", cal.width, cal.height);
    const detail::FpaState state(cal, fpa_temperature_k, "counts → radiance input");
    std::vector<float> radiance(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double d = static_cast<double>(counts[i]) - state.offset(i);
        const double g = state.gain(i);
        // Root of q·L² + g·L − d = 0 written so that q → 0 gives d/g without cancellation.
        const double q = state.quadratic(i);
        const double disc = g * g + 4.0 * q * d;
        radiance[i] = static_cast<float>(disc >= 0.0 ? 2.0 * d / (g + std::sqrt(disc))
                                                     : std::numeric_limits<double>::quiet_NaN());
    }
    replace_bad_pixels(radiance, cal.bad, cal.width, cal.height);
    return radiance;
}

RadiometricCalibration at_fpa_temperature(const RadiometricCalibration& cal,
                                          std::optional<double> fpa_temperature_k,
                                          const std::string& what) {
    const detail::FpaState state(cal, fpa_temperature_k, what);
    RadiometricCalibration out = cal;
    for (std::size_t i = 0; i < cal.gain.size(); ++i) {
        out.offset[i] = static_cast<float>(state.offset(i));
        out.gain[i] = static_cast<float>(state.gain(i));
    }
    out.offset_fpa.clear();
    out.gain_fpa.clear();
    return out;
}

void update_offset(RadiometricCalibration& cal, const BlackbodyFrame& frame) {
    if (!(frame.temperature_k > 0.0) || !std::isfinite(frame.temperature_k))
        fail("{}: offset update needs the blackbody/shutter temperature; got {} K", frame.source,
             frame.temperature_k);
    detail::check_plane(frame.counts, cal.gain.size(), frame.source + " (counts)", cal.width,
                        cal.height);
    const double l = cal.band().radiance(frame.temperature_k);
    const detail::FpaState state(cal, frame.fpa_temperature_k, frame.source);
    // New reference offset o₀' such that o₀' + Σ o_a ΔT^a + g(ΔT)·L + q·L² reproduces the frame.
    std::vector<float> offset(cal.gain.size());
    for (std::size_t i = 0; i < cal.gain.size(); ++i)
        offset[i] = static_cast<float>(frame.counts[i] - (state.offset(i) - cal.offset[i]) -
                                       state.gain(i) * l - state.quadratic(i) * l * l);
    cal.offset = std::move(offset);
}

std::vector<float> brightness_temperature(const Band& band, const std::vector<float>& radiance) {
    std::vector<float> t(radiance.size());
    for (std::size_t i = 0; i < radiance.size(); ++i)
        t[i] = static_cast<float>(band.brightness_temperature(radiance[i]));
    return t;
}

}  // namespace tirpol::calibration
