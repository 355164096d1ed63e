#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <string>

#include "tirpol/calibration/microgrid_session.h"
#include "tirpol/calibration/microgrid_stokes.h"
#include "tirpol/calibration/session_calibration.h"
#include "tirpol/core/error.h"
#include "tirpol/core/session.h"

namespace tirpol::calibration {

namespace fs = std::filesystem;

namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

/// One record's mean frame with what it saw.
struct FlatRecord {
    double radiance = 0.0;  ///< blackbody band radiance L(T), W/(m² sr)
    double two_phi = 0.0;   ///< reference polarizer axis × 2, radians (polarizer records)
    std::vector<float> counts, counts_std;
    std::int64_t frames = 1;
    std::string file;
};

struct FlatSession {
    SessionManifest manifest;
    std::vector<FlatRecord> open, polarized;
    double reference_diattenuation = 1.0;
};

std::string manifest_path(const fs::path& dir) { return (dir / kSessionManifestName).string(); }

double number_field(const nlohmann::json& object, const char* key, const std::string& where) {
    const auto it = object.find(key);
    if (it == object.end() || !it->is_number() || !std::isfinite(it->get<double>()))
        fail("{}.{}: expected a number", where, key);
    return it->get<double>();
}

FlatSession read_flat_session(const fs::path& dir, const Band& band) {
    FlatSession s;
    s.manifest = read_session(dir);
    const SessionManifest& m = s.manifest;
    const std::string path = manifest_path(dir);
    if (!m.camera.microgrid_pattern_deg)
        fail("{}: camera.microgrid_pattern_deg is null: not a microgrid camera's session", path);
    if (const auto it = m.metadata.find("polarizer_in_beam");
        it != m.metadata.end() && it->is_boolean() && it->get<bool>())
        fail(
            "{}: metadata.polarizer_in_beam is true; the blackbody records of a microgrid flat "
            "field must be of the open blackbody (expected false or absent)",
            path);
    std::map<int, double> repeat_temperature_k;
    double offset_deg = 0.0;
    const bool has_polarizer_records =
        std::any_of(m.records.begin(), m.records.end(),
                    [](const SessionRecord& r) { return r.kind == RecordKind::Polarizer; });
    if (has_polarizer_records) {
        const std::string where = path + ": metadata.microgrid_flat_field";
        const auto it = m.metadata.find("microgrid_flat_field");
        if (it == m.metadata.end() || !it->is_object())
            fail(
                "{}: expected an object {{reference_polarizer_axis_offset_deg, polarizer_repeats: "
                "[{{repeat, blackbody_temperature_k}}]}} describing the polarizer records",
                where);
        offset_deg = number_field(*it, "reference_polarizer_axis_offset_deg", where);
        if (it->contains("reference_polarizer_diattenuation")) {
            s.reference_diattenuation =
                number_field(*it, "reference_polarizer_diattenuation", where);
            if (s.reference_diattenuation <= 0.0 || s.reference_diattenuation > 1.0)
                fail("{}.reference_polarizer_diattenuation: {} is outside (0, 1]", where,
                     s.reference_diattenuation);
        }
        const auto reps = it->find("polarizer_repeats");
        if (reps == it->end() || !reps->is_array() || reps->empty())
            fail("{}.polarizer_repeats: expected a list of {{repeat, blackbody_temperature_k}}",
                 where);
        for (std::size_t j = 0; j < reps->size(); ++j) {
            const auto& e = (*reps)[j];
            const std::string at = fmt::format("{}.polarizer_repeats[{}]", where, j);
            if (!e.is_object() || !e.contains("repeat") || !e["repeat"].is_number_integer())
                fail("{}: expected an object with an integer 'repeat'", at);
            const double t = number_field(e, "blackbody_temperature_k", at);
            if (t <= 0.0) fail("{}.blackbody_temperature_k: {} K is not positive", at, t);
            repeat_temperature_k[e["repeat"].get<int>()] = t;
        }
    }
    for (const SessionRecord& r : m.records) {
        if (r.kind == RecordKind::Shutter) continue;
        FlatRecord f;
        f.file = (dir / r.file).string();
        if (r.kind == RecordKind::Blackbody) {
            f.radiance = band.radiance(*r.blackbody_temperature_k);
        } else {
            const auto t = repeat_temperature_k.find(r.repeat);
            if (t == repeat_temperature_k.end())
                fail(
                    "{}: polarizer record {} is of repeat {}, which "
                    "metadata.microgrid_flat_field.polarizer_repeats gives no "
                    "blackbody_temperature_k",
                    path, r.file, r.repeat);
            f.radiance = band.radiance(t->second);
            f.two_phi = 2.0 * kDegToRad * (record_polarizer_angle_deg(m, r) + offset_deg);
        }
        const Image frame = read_session_frame(dir, m, r);
        f.counts = frame.channel("counts");
        f.counts_std = frame.channel("counts_std");
        f.frames = r.frames;
        (r.kind == RecordKind::Blackbody ? s.open : s.polarized).push_back(std::move(f));
    }
    return s;
}

void check_same_camera(const FlatSession& first, const fs::path& first_dir, const FlatSession& s,
                       const fs::path& dir) {
    const SessionCamera &a = first.manifest.camera, &b = s.manifest.camera;
    if (a.width != b.width || a.height != b.height || a.serial != b.serial || a.model != b.model ||
        a.microgrid_pattern_deg != b.microgrid_pattern_deg)
        fail(
            "{}: camera {} {} ({}×{}) differs from that of {} ({} {}, {}×{}) or its pattern does; "
            "expected flat-field sessions of one camera",
            manifest_path(dir), b.model, b.serial, b.width, b.height, manifest_path(first_dir),
            a.model, a.serial, a.width, a.height);
}

std::size_t distinct_values(std::vector<double> values, double tolerance) {
    std::sort(values.begin(), values.end());
    std::size_t count = 0;
    for (std::size_t i = 0; i < values.size(); ++i)
        if (i == 0 || values[i] - values[i - 1] > tolerance) ++count;
    return count;
}

double wrap_pm90(double angle_deg) {
    double a = std::fmod(angle_deg + 90.0, 180.0);
    if (a < 0.0) a += 180.0;
    return a - 90.0;
}

/// Σ_j σ_ij²·p_j·p_jᵀ over `records` (σ_ij² = counts_std²/frames, the variance of the record's
/// mean frame at pixel i), p_j column j of `pinv`.
template <int P>
Eigen::Matrix<double, P, P> fit_covariance(const Eigen::MatrixXd& pinv,
                                           const std::vector<FlatRecord>& records, std::size_t i) {
    Eigen::Matrix<double, P, P> covariance = Eigen::Matrix<double, P, P>::Zero();
    for (std::size_t j = 0; j < records.size(); ++j) {
        const double sigma = records[j].counts_std[i];
        const Eigen::Matrix<double, P, 1> column = pinv.col(static_cast<Eigen::Index>(j));
        covariance +=
            (sigma * sigma / static_cast<double>(records[j].frames)) * column * column.transpose();
    }
    return covariance;
}

/// Pixel i's covariance of (w0, w1, w2, b) = (g, g·m1/a, g·m2/a, b) to first order, from the
/// NUC fit's (g, b) and the analyzer fit's (a, m1, m2, b'), independent (disjoint records).
void store_parameter_covariance(MicrogridPixelCalibration& cal, std::size_t i,
                                const Eigen::MatrixXd& nuc_pinv,
                                const std::vector<FlatRecord>& open,
                                const Eigen::MatrixXd& analyzer_pinv,
                                const std::vector<FlatRecord>& polarized, double g, double m1,
                                double m2, double a) {
    Eigen::Matrix<double, 4, 2> nuc_jacobian;
    nuc_jacobian << 1.0, 0.0, m1 / a, 0.0, m2 / a, 0.0, 0.0, 1.0;
    Eigen::Matrix4d analyzer_jacobian = Eigen::Matrix4d::Zero();
    analyzer_jacobian.row(1) << -g * m1 / (a * a), g / a, 0.0, 0.0;
    analyzer_jacobian.row(2) << -g * m2 / (a * a), 0.0, g / a, 0.0;
    const Eigen::Matrix4d covariance =
        nuc_jacobian * fit_covariance<2>(nuc_pinv, open, i) * nuc_jacobian.transpose() +
        analyzer_jacobian * fit_covariance<4>(analyzer_pinv, polarized, i) *
            analyzer_jacobian.transpose();
    std::size_t e = 0;
    for (Eigen::Index r = 0; r < 4; ++r)
        for (Eigen::Index c = r; c < 4; ++c)
            cal.parameter_covariance[e++][i] = static_cast<float>(covariance(r, c));
}

}  // namespace

std::size_t MicrogridFlatFieldCalibration::bad_count(std::uint32_t bits) const {
    return static_cast<std::size_t>(
        std::count_if(pixels.bad.begin(), pixels.bad.end(),
                      [bits](float b) { return (static_cast<std::uint32_t>(b) & bits) != 0; }));
}

MicrogridFlatFieldCalibration calibrate_microgrid_sessions(
    const std::vector<fs::path>& dirs, const Band& band, const MicrogridFlatFieldOptions& options) {
    if (dirs.empty()) fail("microgrid calibration: no flat-field session given");
    std::vector<FlatRecord> open, polarized;
    std::optional<FlatSession> first;
    std::optional<double> saturation;
    std::string where = manifest_path(dirs.front());
    double reference_diattenuation = 1.0;
    for (const fs::path& dir : dirs) {
        FlatSession s = read_flat_session(dir, band);
        if (first) {
            check_same_camera(*first, dirs.front(), s, dir);
            if (s.reference_diattenuation != reference_diattenuation)
                fail(
                    "{}: metadata.microgrid_flat_field.reference_polarizer_diattenuation {} "
                    "differs "
                    "from {} in {}; expected one reference polarizer",
                    manifest_path(dir), s.reference_diattenuation, reference_diattenuation, where);
        } else {
            reference_diattenuation = s.reference_diattenuation;
            saturation = session_saturation_counts(s.manifest);
        }
        for (auto& r : s.open) open.push_back(std::move(r));
        for (auto& r : s.polarized) polarized.push_back(std::move(r));
        s.open.clear();
        s.polarized.clear();
        if (!first) first = std::move(s);
    }
    if (dirs.size() > 1) where = fmt::format("{} and {} other session(s)", where, dirs.size() - 1);
    const SessionCamera& camera = first->manifest.camera;
    const int width = camera.width, height = camera.height;
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    const MicrogridPattern pattern(*camera.microgrid_pattern_deg,
                                   where + ": camera.microgrid_pattern_deg");

    std::vector<double> open_radiance, pol_radiance, pol_angle_deg;
    for (const auto& r : open) open_radiance.push_back(r.radiance);
    for (const auto& r : polarized) {
        pol_radiance.push_back(r.radiance);
        pol_angle_deg.push_back(
            std::fmod(std::fmod(r.two_phi / (2.0 * kDegToRad), 180.0) + 180.0, 180.0));
    }
    if (distinct_values(open_radiance, 1e-9) < 2)
        fail(
            "{}: {} open-blackbody record(s) at {} temperature(s); the two-point NUC needs "
            "blackbody "
            "records at ≥ 2 temperatures (polarizer out of the beam)",
            where, open.size(), distinct_values(open_radiance, 1e-9));
    if (distinct_values(pol_radiance, 1e-9) < 2 || distinct_values(pol_angle_deg, 0.5) < 3)
        fail(
            "{}: {} polarizer record(s) at {} blackbody temperature(s) and {} angle(s); the "
            "analyzer fit needs the reference polarizer at ≥ 3 angles and ≥ 2 blackbody "
            "temperatures",
            where, polarized.size(), distinct_values(pol_radiance, 1e-9),
            distinct_values(pol_angle_deg, 0.5));

    // Analyzer: counts = a·L + L·(m1 cos 2φ + m2 sin 2φ) + b', the Powell & Gruev fit with a
    // background; the reference polarizer's diattenuation scales the polarized part of the source.
    std::vector<MicrogridFlatField> fields;
    for (const auto& r : polarized)
        fields.push_back(
            {Eigen::Vector3d(r.radiance, reference_diattenuation * r.radiance * std::cos(r.two_phi),
                             reference_diattenuation * r.radiance * std::sin(r.two_phi)),
             r.counts});
    const MicrogridPixelCalibration analyzer = calibrate_microgrid_pixels(fields, width, height);

    // Each record's mean frame has the temporal σ counts_std/√frames; both fits are linear least
    // squares with one design for every pixel, so a pixel's parameters have the covariance
    // Σ_j σ_ij²·p_j·p_jᵀ (p_j column j of the design's pseudo-inverse). Needs every record's σ.
    const auto has_std = [](const FlatRecord& r) { return r.frames > 1; };
    const bool temporal_noise_known = std::all_of(open.begin(), open.end(), has_std) &&
                                      std::all_of(polarized.begin(), polarized.end(), has_std);
    Eigen::MatrixXd nuc_pinv, analyzer_pinv;
    if (temporal_noise_known) {
        Eigen::MatrixXd nuc_design(static_cast<Eigen::Index>(open.size()), 2);
        for (std::size_t j = 0; j < open.size(); ++j)
            nuc_design.row(static_cast<Eigen::Index>(j)) << open[j].radiance, 1.0;
        nuc_pinv = nuc_design.completeOrthogonalDecomposition().pseudoInverse();
        Eigen::MatrixXd analyzer_design(static_cast<Eigen::Index>(fields.size()), 4);
        for (std::size_t j = 0; j < fields.size(); ++j)
            analyzer_design.row(static_cast<Eigen::Index>(j))
                << fields[j].source_stokes.transpose(),
                1.0;
        analyzer_pinv = analyzer_design.completeOrthogonalDecomposition().pseudoInverse();
    }

    // Two-point NUC (least squares over ≥ 2 temperatures): counts = g·L + b.
    double mean_l = 0.0;
    for (double l : open_radiance) mean_l += l;
    mean_l /= static_cast<double>(open.size());
    double sxx = 0.0;
    for (double l : open_radiance) sxx += (l - mean_l) * (l - mean_l);

    MicrogridFlatFieldCalibration out;
    out.open_blackbody_records = open.size();
    out.polarizer_records = polarized.size();
    MicrogridPixelCalibration& cal = out.pixels;
    cal.width = width;
    cal.height = height;
    cal.stokes_units = "W/(m^2 sr)";
    cal.fit_rms = analyzer.fit_rms;
    for (auto& plane : cal.analysis) plane.assign(n, 0.0f);
    cal.background.assign(n, 0.0f);
    if (temporal_noise_known)
        for (auto& plane : cal.parameter_covariance) plane.assign(n, 0.0f);
    std::vector<std::uint32_t> bad(n, kGood);
    std::vector<float> gain(n), offset(n), residual(n), noise(n), noise_of_mean(n);
    double nuc_sum_sq = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        double mean_c = 0.0, sxy = 0.0;
        for (const auto& r : open) mean_c += r.counts[i];
        mean_c /= static_cast<double>(open.size());
        for (const auto& r : open) sxy += (r.radiance - mean_l) * (r.counts[i] - mean_c);
        const double g = sxy / sxx;
        const double b = mean_c - g * mean_l;
        gain[i] = static_cast<float>(g);
        offset[i] = static_cast<float>(b);
        double sum_sq = 0.0, std_sum = 0.0, std_of_mean_sum = 0.0;
        std::size_t with_std = 0;
        for (const auto& r : open) {
            const double e = r.counts[i] - (g * r.radiance + b);
            sum_sq += e * e;
            nuc_sum_sq += e * e;
        }
        const double a = analyzer.analysis[0][i];
        for (const MicrogridFlatField& f : fields) {
            const double predicted =
                a * f.source_stokes(0) + analyzer.analysis[1][i] * f.source_stokes(1) +
                analyzer.analysis[2][i] * f.source_stokes(2) + analyzer.background[i];
            const double e = f.frame[i] - predicted;
            sum_sq += e * e;
        }
        for (const auto* records : {&open, &polarized})
            for (const auto& r : *records) {
                if (saturation && r.counts[i] >= *saturation) bad[i] |= kSaturated;
                if (r.frames > 1) {
                    std_sum += r.counts_std[i];
                    std_of_mean_sum += r.counts_std[i] / std::sqrt(static_cast<double>(r.frames));
                    ++with_std;
                }
            }
        residual[i] = static_cast<float>(
            std::sqrt(sum_sq / static_cast<double>(open.size() + polarized.size())));
        noise[i] = with_std ? static_cast<float>(std_sum / static_cast<double>(with_std)) : kNaN;
        noise_of_mean[i] =
            with_std ? static_cast<float>(std_of_mean_sum / static_cast<double>(with_std)) : kNaN;
        // w = g·(1, (m1, m2)/a): the NUC's gain with the analyzer's polarized fraction and axis.
        cal.analysis[0][i] = static_cast<float>(g);
        cal.analysis[1][i] = static_cast<float>(g * analyzer.analysis[1][i] / a);
        cal.analysis[2][i] = static_cast<float>(g * analyzer.analysis[2][i] / a);
        cal.background[i] = static_cast<float>(b);
        if (temporal_noise_known)
            store_parameter_covariance(cal, i, nuc_pinv, open, analyzer_pinv, polarized, g,
                                       analyzer.analysis[1][i], analyzer.analysis[2][i], a);
    }
    out.nuc_fit_rms_counts = std::sqrt(nuc_sum_sq / static_cast<double>(n * open.size()));

    // Bad pixels: thresholds of bad_pixels.h on gain, offset, temporal noise and fit residual,
    // plus implausible analyzers.
    const BadPixelThresholds& th = options.thresholds;
    const RobustStats g_stats = robust_stats(gain), b_stats = robust_stats(offset),
                      n_stats = robust_stats(noise), r_stats = robust_stats(residual);
    std::vector<float> dia(n), axis_err(n);
    for (std::size_t i = 0; i < n; ++i) {
        const int x = static_cast<int>(i % static_cast<std::size_t>(width));
        const int y = static_cast<int>(i / static_cast<std::size_t>(width));
        if (!(gain[i] > th.dead_gain_fraction * g_stats.median)) bad[i] |= kDead;
        if (offset[i] > b_stats.median + th.hot_sigma * b_stats.sigma) bad[i] |= kHot;
        if (std::isfinite(noise[i]) && noise[i] > th.noisy_factor * n_stats.median)
            bad[i] |= kNoisy;
        const double explained = std::isfinite(noise_of_mean[i]) ? 3.0 * noise_of_mean[i] : 0.0;
        if (residual[i] > r_stats.median + th.nonlinear_sigma * r_stats.sigma &&
            residual[i] > explained)
            bad[i] |= kNonLinear;
        const double d = cal.diattenuation(i);
        const double err = wrap_pm90(cal.axis_angle_deg(i) - pattern.angle_at_pixel_deg(x, y));
        dia[i] = static_cast<float>(d);
        axis_err[i] = static_cast<float>(err);
        if (!(d >= options.min_diattenuation && d <= 1.05) ||
            !(std::abs(err) <= options.max_axis_error_deg))
            bad[i] |= kBadAnalyzer;
    }
    cal.bad.resize(n);
    std::vector<float> good_gain, good_dia;
    double axis_sq = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        cal.bad[i] = static_cast<float>(bad[i]);
        if (bad[i] != kGood) continue;
        good_gain.push_back(gain[i]);
        good_dia.push_back(dia[i]);
        axis_sq += static_cast<double>(axis_err[i]) * axis_err[i];
    }
    if (good_gain.empty())
        fail(
            "{}: every pixel was found bad (dead, hot, noisy, non-linear, saturated or a bad "
            "analyzer); expected flat fields of a working camera",
            where);
    const RobustStats good_g = robust_stats(good_gain), good_d = robust_stats(good_dia);
    out.gain_rel_spread = good_g.sigma / good_g.median;
    out.diattenuation_median = good_d.median;
    out.diattenuation_spread = good_d.sigma;
    out.axis_error_rms_deg = std::sqrt(axis_sq / static_cast<double>(good_gain.size()));

    out.nuc_only = cal;
    for (auto& plane : out.nuc_only.parameter_covariance) plane.clear();  // a comparison only
    for (std::size_t i = 0; i < n; ++i) {
        const double two_theta =
            2.0 * kDegToRad *
            pattern.angle_at_pixel_deg(static_cast<int>(i % static_cast<std::size_t>(width)),
                                       static_cast<int>(i / static_cast<std::size_t>(width)));
        out.nuc_only.analysis[1][i] = static_cast<float>(gain[i] * std::cos(two_theta));
        out.nuc_only.analysis[2][i] = static_cast<float>(gain[i] * std::sin(two_theta));
    }
    return out;
}

}  // namespace tirpol::calibration
