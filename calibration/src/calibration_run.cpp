#include <fmt/printf.h>

#include <cmath>

#include "tirpol/calibration/calibration_chain.h"
#include "tirpol/calibration/radiometric.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/output_guard.h"

namespace tirpol::calibration {

RadiometricRun run_radiometric_calibration(const RadiometricRunOptions& o) {
    std::optional<SpectralResponse> rsr;
    if (!o.rsr.empty()) rsr = SpectralResponse::load_csv(o.rsr);
    ChainInputs chain;
    chain.band = Band(o.band_um[0], o.band_um[1], rsr);
    chain.blackbody_sessions = {o.sessions.begin(), o.sessions.end()};
    chain.radiometric_options.quadratic = o.quadratic;
    chain.radiometric_options.saturation_counts = o.saturation_counts;
    chain.radiometric_options.fpa_degree = o.fpa_degree;
    chain.assess_quality = true;
    auto products = run_calibration_chain(chain);
    RadiometricRun run{o, std::move(*products.radiometric), std::move(*products.quality)};
    write_radiometric_calibration(o.output, run.calibration);
    write_calibration_summary(o.summary, run.calibration, run.quality);
    return run;
}

std::string radiometric_run_text(const RadiometricRun& run) {
    const auto& cal = run.calibration;
    const auto& quality = run.quality;
    const auto gain = robust_stats(cal.gain);
    const auto residual = robust_stats(cal.residual_rms);
    std::string text =
        fmt::sprintf("radiometric calibration of %s (%d×%d, %zu blackbody frames, %s model)\n",
                     cal.camera_id, cal.width, cal.height, cal.temperatures_k.size(),
                     run.options.quadratic ? "quadratic" : "linear");
    text += fmt::sprintf("  median gain %.4g counts/(W/(m²·sr)), median residual %.3g counts\n",
                         gain.median, residual.median);
    if (cal.fpa_degree() > 0)
        text += fmt::sprintf(
            "  FPA-temperature model of degree %d about %.2f K, calibrated over FPA %.2f–%.2f K "
            "(%zu session(s))\n",
            cal.fpa_degree(), cal.fpa_reference_k, cal.fpa_min_k, cal.fpa_max_k,
            run.options.sessions.size());
    text += "  residual per set-point (mean over good pixels, mK):\n";
    for (const auto& s : quality.set_points)
        text += fmt::sprintf("    %8.2f K%s: mean %+7.1f mK, RMS %6.1f mK\n", s.temperature_k,
                             std::isfinite(s.fpa_temperature_k)
                                 ? fmt::format(" at FPA {:.2f} K", s.fpa_temperature_k)
                                 : "",
                             s.mean_mk, s.rms_mk);
    text += fmt::sprintf("  median NEDT %.1f mK at %.1f K\n", 1000.0 * quality.nedt_median_k,
                         quality.nedt_temperature_k);
    for (const auto& w : cal.warnings) text += "  warning: " + w + "\n";
    text += fmt::sprintf(
        "  bad pixels: %zu (dead %zu, hot %zu, noisy %zu, non-linear %zu, saturated %zu)\n",
        cal.bad_count(), cal.bad_count(kDead), cal.bad_count(kHot), cal.bad_count(kNoisy),
        cal.bad_count(kNonLinear), cal.bad_count(kSaturated));
    return text + fmt::sprintf(
                      "  written: %s and %s/ (index.html, maps.exr, nedt.png, bad_pixels.png, "
                      "residuals.png)\n",
                      run.options.output, run.options.summary);
}

PolarimetricCalibration run_polarimetric_calibration(const PolarimetricRunOptions& o) {
    ChainInputs chain;
    chain.polarimetric_session = o.session;
    if (o.extinction_ratio)
        chain.datasheet = DatasheetAnalyzer{*o.extinction_ratio, o.axis_offsets_deg};
    ChainProducts given;
    given.radiometric = read_radiometric_calibration(o.calibration);
    auto pol = *run_calibration_chain(chain, std::move(given)).polarimetric;
    pol.radiometric_calibration = o.calibration;
    write_polarimetric_calibration(o.output, pol);
    return pol;
}

std::string polarimetric_calibration_text(const PolarimetricCalibration& pol,
                                          const PolarimetricRunOptions& o) {
    std::string text = fmt::sprintf("polarimetric calibration of %s: analyzer by %s\n", o.session,
                                    pol.analyzer_method);
    for (const auto& p : pol.analyzer.positions)
        text += fmt::sprintf(
            "  %6.2f°: axis %7.3f°, extinction ratio %8.4g, relative transmission %.4f\n",
            p.nominal_angle_deg, p.axis_angle_deg, p.extinction_ratio(), p.relative_transmission);
    text += fmt::sprintf("  condition number of W: %.4f\n", pol.analyzer.condition_number());
    return text +
           fmt::sprintf("  written: %s and %s\n", o.output, polarimetric_maps_path(o.output));
}

void check_radiometric_run(const RadiometricRunOptions& o, bool force) {
    OutputGuard guard;
    for (const std::string& session : o.sessions) guard.input(session, "SESSION");
    guard.input(o.rsr, "--rsr")
        .output_file(o.output, "--output")
        .output_folder(o.summary, "--summary",
                       {"index.html", "maps.exr", "nedt.png", "bad_pixels.png", "residuals.png"})
        .check(force);
}

void check_polarimetric_run(const PolarimetricRunOptions& o, bool force) {
    OutputGuard()
        .input(o.session, "SESSION")
        .input(o.calibration, "--calibration")
        .output_file(o.output, "--output")
        .output_file(polarimetric_maps_path(o.output), "--output (maps)")
        .check(force);
    if (!o.extinction_ratio && !o.axis_offsets_deg.empty())
        throw OptionValueError("--axis-offset-deg",
                               "needs --extinction-ratio (the datasheet's t_max/t_min)");
}

}  // namespace tirpol::calibration
