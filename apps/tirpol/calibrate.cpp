// `tirpol calibrate radiometric|polarimetric`: blackbody count→radiance calibration and the
// polarizer/wire-grid calibration from capture sessions (docs/calibration.md).

#include <memory>

#include "cli.h"
#include "common_options.h"
#include "tirpol/calibration/calibration_chain.h"

namespace tirpol::cli {

namespace {
struct RadiometricArgs {
    calibration::RadiometricRunOptions options;
    std::vector<double> band_um{8.0, 14.0};
    bool force = false;
};

void run_radiometric(RadiometricArgs& a) {
    auto& o = a.options;
    if (o.summary.empty()) o.summary = calibration::default_summary_dir(o.output);
    o.band_um = {a.band_um[0], a.band_um[1]};
    calibration::check_radiometric_run(o, a.force);
    print_text(calibration::radiometric_run_text(calibration::run_radiometric_calibration(o)));
}

struct PolarimetricArgs {
    calibration::PolarimetricRunOptions options;
    bool force = false;
};

void run_polarimetric(const PolarimetricArgs& a) {
    calibration::check_polarimetric_run(a.options, a.force);
    print_text(calibration::polarimetric_calibration_text(
        calibration::run_polarimetric_calibration(a.options), a.options));
}

void register_calibrate(CLI::App& app) {
    auto* cmd = app.add_subcommand(
        "calibrate",
        "Radiometric (blackbody), polarimetric (wire grid), geometric (lens) or pose calibration");
    cmd->require_subcommand(1);

    auto r = std::make_shared<RadiometricArgs>();
    auto* rad = cmd->add_subcommand(
        "radiometric", "Per-pixel counts→radiance, bad pixels, from blackbody records");
    auto& ro = r->options;
    add_required_input(rad, "SESSION", ro.sessions,
                       "Session directories with blackbody records (one camera; several camera "
                       "temperatures for --fpa-degree)",
                       CLI::ExistingDirectory);
    add_output_option(rad, ro.output, "Calibration EXR to write");
    add_band_options(rad, r->band_um, ro.rsr)->capture_default_str();
    rad->add_flag("--quadratic", ro.quadratic, "Fit counts = o + g·L + q·L² (≥ 3 temperatures)");
    rad->add_option("--fpa-degree", ro.fpa_degree,
                    "Gain and offset as polynomials of this degree in the camera's FPA temperature "
                    "(0: one camera state; 1: Nugent et al. 2013)")
        ->check(CLI::Range(0, 2))
        ->capture_default_str();
    rad->add_option("--summary", ro.summary,
                    "Directory of the one-page HTML/PNG summary (default: next to -o, .summary)");
    rad->add_option("--saturation-counts", ro.saturation_counts,
                    "Saturation level (default 2^bits − 1 of the camera)");
    add_force_flag(rad, r->force);
    rad->callback([r] { run_radiometric(*r); });

    auto p = std::make_shared<PolarimetricArgs>();
    auto* pol = cmd->add_subcommand(
        "polarimetric",
        "Wire-grid τ/B maps and analyzer model from blackbody/known-source records");
    auto& po = p->options;
    add_required_input(pol, "SESSION", po.session,
                       "Session with blackbody records through the polarizer",
                       CLI::ExistingDirectory);
    add_required_input(pol, "--calibration", po.calibration, "Radiometric calibration EXR");
    add_output_option(pol, po.output, "Polarimetric calibration YAML (maps next to it, .maps.exr)");
    pol->add_option("--extinction-ratio", po.extinction_ratio,
                    "Datasheet extinction ratio t_max/t_min of the polarizer, used without "
                    "known-source records");
    pol->add_option("--axis-offset-deg", po.axis_offsets_deg,
                    "Datasheet/mount axis offset(s) in degrees: one for all angles or one per "
                    "angle (ascending)");
    add_force_flag(pol, p->force);
    pol->callback([p] { run_polarimetric(*p); });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(50, register_calibrate);

}  // namespace tirpol::cli
