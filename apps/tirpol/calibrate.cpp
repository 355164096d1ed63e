// `tirpol calibrate radiometric|polarimetric`: blackbody count→radiance calibration and the
// polarizer/wire-grid calibration from capture sessions (docs/calibration.md).

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "cli.h"
#include "tirpol/calibration/calibration_chain.h"
#include "tirpol/core/error.h"

namespace tirpol::cli {

namespace {
struct RadiometricArgs {
    std::vector<std::string> sessions;
    std::string output, rsr, summary;
    int fpa_degree = 0;
    std::vector<double> band_um{8.0, 14.0};
    bool quadratic = false;
    bool force = false;
    std::optional<double> saturation_counts;
};

void run_radiometric(const RadiometricArgs& a) {
    const std::string summary =
        a.summary.empty() ? calibration::default_summary_dir(a.output) : a.summary;
    OutputGuard guard;
    for (const std::string& session : a.sessions) guard.input(session, "SESSION");
    guard.input(a.rsr, "--rsr")
        .output_file(a.output, "--output")
        .output_folder(summary, "--summary",
                       {"index.html", "maps.exr", "nedt.png", "bad_pixels.png", "residuals.png"})
        .check(a.force);
    std::optional<SpectralResponse> rsr;
    if (!a.rsr.empty()) rsr = SpectralResponse::load_csv(a.rsr);
    const Band band(a.band_um[0], a.band_um[1], rsr);
    calibration::ChainInputs chain;
    chain.band = band;
    chain.blackbody_sessions = {a.sessions.begin(), a.sessions.end()};
    chain.radiometric_options.quadratic = a.quadratic;
    chain.radiometric_options.saturation_counts = a.saturation_counts;
    chain.radiometric_options.fpa_degree = a.fpa_degree;
    chain.assess_quality = true;
    const auto products = calibration::run_calibration_chain(chain);
    const auto& cal = *products.radiometric;
    const auto& quality = *products.quality;
    calibration::write_radiometric_calibration(a.output, cal);
    calibration::write_calibration_summary(summary, cal, quality);
    const auto gain = calibration::robust_stats(cal.gain);
    const auto residual = calibration::robust_stats(cal.residual_rms);
    std::printf("radiometric calibration of %s (%d×%d, %zu blackbody frames, %s model)\n",
                cal.camera_id.c_str(), cal.width, cal.height, cal.temperatures_k.size(),
                a.quadratic ? "quadratic" : "linear");
    std::printf("  median gain %.4g counts/(W/(m²·sr)), median residual %.3g counts\n", gain.median,
                residual.median);
    if (cal.fpa_degree() > 0)
        std::printf(
            "  FPA-temperature model of degree %d about %.2f K, calibrated over FPA %.2f–%.2f K "
            "(%zu session(s))\n",
            cal.fpa_degree(), cal.fpa_reference_k, cal.fpa_min_k, cal.fpa_max_k, a.sessions.size());
    std::printf("  residual per set-point (mean over good pixels, mK):\n");
    for (const auto& s : quality.set_points)
        std::printf("    %8.2f K%s: mean %+7.1f mK, RMS %6.1f mK\n", s.temperature_k,
                    std::isfinite(s.fpa_temperature_k)
                        ? fmt::format(" at FPA {:.2f} K", s.fpa_temperature_k).c_str()
                        : "",
                    s.mean_mk, s.rms_mk);
    std::printf("  median NEDT %.1f mK at %.1f K\n", 1000.0 * quality.nedt_median_k,
                quality.nedt_temperature_k);
    for (const auto& w : cal.warnings) std::printf("  warning: %s\n", w.c_str());
    std::printf("  bad pixels: %zu (dead %zu, hot %zu, noisy %zu, non-linear %zu, saturated %zu)\n",
                cal.bad_count(), cal.bad_count(calibration::kDead),
                cal.bad_count(calibration::kHot), cal.bad_count(calibration::kNoisy),
                cal.bad_count(calibration::kNonLinear), cal.bad_count(calibration::kSaturated));
    std::printf(
        "  written: %s and %s/ (index.html, maps.exr, nedt.png, bad_pixels.png, residuals.png)\n",
        a.output.c_str(), summary.c_str());
}

struct PolarimetricArgs {
    std::string session, calibration, output;
    std::optional<double> extinction_ratio;
    std::vector<double> axis_offsets_deg;
    bool force = false;
};

void run_polarimetric(const PolarimetricArgs& a) {
    OutputGuard()
        .input(a.session, "SESSION")
        .input(a.calibration, "--calibration")
        .output_file(a.output, "--output")
        .output_file(calibration::polarimetric_maps_path(a.output), "--output (maps)")
        .check(a.force);
    if (!a.extinction_ratio && !a.axis_offsets_deg.empty())
        usage_error("--axis-offset-deg", "needs --extinction-ratio (the datasheet's t_max/t_min)");
    calibration::ChainInputs chain;
    chain.polarimetric_session = a.session;
    if (a.extinction_ratio)
        chain.datasheet = calibration::DatasheetAnalyzer{*a.extinction_ratio, a.axis_offsets_deg};
    calibration::ChainProducts given;
    given.radiometric = calibration::read_radiometric_calibration(a.calibration);
    auto pol = *calibration::run_calibration_chain(chain, std::move(given)).polarimetric;
    pol.radiometric_calibration = a.calibration;
    calibration::write_polarimetric_calibration(a.output, pol);
    std::printf("polarimetric calibration of %s: analyzer by %s\n", a.session.c_str(),
                pol.analyzer_method.c_str());
    for (const auto& p : pol.analyzer.positions)
        std::printf("  %6.2f°: axis %7.3f°, extinction ratio %8.4g, relative transmission %.4f\n",
                    p.nominal_angle_deg, p.axis_angle_deg, p.extinction_ratio(),
                    p.relative_transmission);
    std::printf("  condition number of W: %.4f\n", pol.analyzer.condition_number());
    std::printf("  written: %s and %s\n", a.output.c_str(),
                calibration::polarimetric_maps_path(a.output).c_str());
}

void register_calibrate(CLI::App& app) {
    auto* cmd = app.add_subcommand(
        "calibrate",
        "Radiometric (blackbody), polarimetric (wire grid), geometric (lens) or pose calibration");
    cmd->require_subcommand(1);

    auto r = std::make_shared<RadiometricArgs>();
    auto* rad = cmd->add_subcommand(
        "radiometric", "Per-pixel counts→radiance, bad pixels, from blackbody records");
    rad->add_option("SESSION", r->sessions,
                    "Session directories with blackbody records (one camera; several camera "
                    "temperatures for --fpa-degree)")
        ->required()
        ->check(CLI::ExistingDirectory);
    rad->add_option("-o,--output", r->output, "Calibration EXR to write")->required();
    rad->add_option("--band-um", r->band_um, "Band limits LO HI in micrometres")
        ->expected(2)
        ->capture_default_str();
    rad->add_option("--rsr", r->rsr, "Relative spectral response CSV (wavelength_um,response)")
        ->check(CLI::ExistingFile);
    rad->add_flag("--quadratic", r->quadratic, "Fit counts = o + g·L + q·L² (≥ 3 temperatures)");
    rad->add_option("--fpa-degree", r->fpa_degree,
                    "Gain and offset as polynomials of this degree in the camera's FPA temperature "
                    "(0: one camera state; "
                    "1: Nugent et al. 2013)")
        ->check(CLI::Range(0, 2))
        ->capture_default_str();
    rad->add_option("--summary", r->summary,
                    "Directory of the one-page HTML/PNG summary (default: next to -o, .summary)");
    rad->add_option("--saturation-counts", r->saturation_counts,
                    "Saturation level (default 2^bits − 1 of the camera)");
    add_force_flag(rad, r->force);
    rad->callback([r] { run_radiometric(*r); });

    auto p = std::make_shared<PolarimetricArgs>();
    auto* pol = cmd->add_subcommand(
        "polarimetric",
        "Wire-grid τ/B maps and analyzer model from blackbody/known-source records");
    pol->add_option("SESSION", p->session, "Session with blackbody records through the polarizer")
        ->required()
        ->check(CLI::ExistingDirectory);
    pol->add_option("--calibration", p->calibration, "Radiometric calibration EXR")
        ->required()
        ->check(CLI::ExistingFile);
    pol->add_option("-o,--output", p->output,
                    "Polarimetric calibration YAML (maps next to it, .maps.exr)")
        ->required();
    pol->add_option("--extinction-ratio", p->extinction_ratio,
                    "Datasheet extinction ratio t_max/t_min of the polarizer, used without "
                    "known-source records");
    pol->add_option("--axis-offset-deg", p->axis_offsets_deg,
                    "Datasheet/mount axis offset(s) in degrees: one for all angles or one per "
                    "angle (ascending)");
    add_force_flag(pol, p->force);
    pol->callback([p] { run_polarimetric(*p); });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(50, register_calibrate);

}  // namespace tirpol::cli
