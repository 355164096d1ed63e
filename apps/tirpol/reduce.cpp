// `tirpol reduce`: a session of raw counts → calibrated Stokes EXR (S0 S1 S2 DoLP AoP + *_std).

#include <memory>

#include "cli.h"
#include "common_options.h"
#include "tirpol/calibration/calibration_chain.h"
#include "tirpol/calibration/microgrid_run.h"

namespace tirpol::cli {

namespace {
struct ReduceArgs {
    std::string session, calibration, polarimetric, output, quicklooks;
    std::string pixel_calibration, method = "newton";
    bool update_offset = false;
    bool drift_correction = false;
    bool slar = false;
    bool other_camera = false;
    bool force = false;
    double max_saturated_fraction = 0.01;
};

void run_reduce(const ReduceArgs& a) {
    if (calibration::is_readable_microgrid_session(a.session)) {
        for (const auto& [given, name] :
             {std::pair{!a.calibration.empty(), "--calibration"},
              std::pair{!a.polarimetric.empty(), "--polarimetric"},
              std::pair{a.update_offset, "--update-offset"},
              std::pair{a.drift_correction, "--drift-correction"}, std::pair{a.slar, "--slar"},
              std::pair{a.other_camera, "--other-camera"}})
            if (given)
                usage_error(name,
                            "{} is for a rotating-polarizer session; {} is a microgrid camera's "
                            "session (use --pixel-calibration and --method)",
                            name, a.session);
        return print_text(
            calibration::microgrid_reduce_run_text(calibration::run_microgrid_reduction(
                {a.session, a.output, a.quicklooks, a.pixel_calibration, a.method, a.force})));
    }
    // Anything else is left to the rotating-polarizer path, which checks the outputs first and
    // then reports what is wrong with the session.
    if (!a.pixel_calibration.empty())
        usage_error("--pixel-calibration",
                    "{} is not a microgrid camera's session (its manifest records no microgrid "
                    "pattern): --pixel-calibration is for microgrid sessions",
                    a.session);
    const calibration::SessionToStokesOptions o{
        a.session,      a.calibration,           a.polarimetric,     a.output,
        a.quicklooks,   a.update_offset,         a.drift_correction, a.slar,
        a.other_camera, a.max_saturated_fraction};
    calibration::check_session_to_stokes(o, a.force);
    print_text(calibration::session_to_stokes_text(calibration::session_to_stokes(o)));
}

void register_reduce(CLI::App& app) {
    auto a = std::make_shared<ReduceArgs>();
    auto* cmd =
        app.add_subcommand("reduce", "Session → Stokes EXR (S0 S1 S2 DoLP AoP and uncertainties)");
    add_required_input(cmd, "SESSION", a->session, "Session directory with polarizer records",
                       CLI::ExistingDirectory);
    cmd->add_option("--calibration", a->calibration,
                    "Radiometric calibration EXR (rotating-polarizer session; without it, a "
                    "Stokes quick look in counts, not radiance)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--pixel-calibration", a->pixel_calibration,
                    "Microgrid session: per-pixel analyzer calibration EXR (w0 w1 w2 background); "
                    "reduces per 2×2 super-pixel")
        ->check(CLI::ExistingFile);
    cmd->add_option("--method", a->method,
                    "Microgrid session without --pixel-calibration: demosaicing, super-pixel, "
                    "bilinear or newton")
        ->capture_default_str();
    cmd->add_option("--polarimetric", a->polarimetric,
                    "Polarimetric calibration YAML (wire-grid removal, analyzer model)")
        ->check(CLI::ExistingFile);
    cmd->add_flag("--update-offset", a->update_offset,
                  "Update the offset from the session's shutter/blackbody record");
    cmd->add_flag("--drift-correction", a->drift_correction,
                  "Correct each record for the offset drift during the session (plan "
                  "scene_reference region, else interleaved shutter records with a temperature)");
    cmd->add_option("--max-saturated-fraction", a->max_saturated_fraction,
                    "Error above this saturated fraction")
        ->capture_default_str();
    cmd->add_flag("--slar", a->slar,
                  "Also write L_SLAR_<angle> channels (wire-grid-corrected radiance per angle)");
    cmd->add_flag("--other-camera", a->other_camera,
                  "Apply a calibration made with another camera (serial/model/bit depth differ)");
    add_force_flag(cmd, a->force);
    cmd->add_option("--quicklooks", a->quicklooks,
                    "Also write S0/S1/S2/DoLP/AoP PNGs to this folder");
    cmd->add_option("-o,--output", a->output, "Stokes EXR to write")->required();
    cmd->callback([a] { run_reduce(*a); });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(55, register_reduce);

}  // namespace tirpol::cli
