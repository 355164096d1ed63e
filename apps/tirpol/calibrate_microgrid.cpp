// `tirpol calibrate microgrid`: a microgrid camera's per-pixel calibration (two-point NUC, each
// pixel's analyzer, bad pixels) from flat-field sessions (docs/microgrid.md).

#include <memory>

#include "cli.h"
#include "common_options.h"
#include "tirpol/calibration/microgrid_run.h"

namespace tirpol::cli {

namespace {
struct MicrogridCalibrationArgs {
    calibration::MicrogridCalibrationRunOptions options;
    std::vector<double> band_um{8.0, 14.0};
};

void register_calibrate_microgrid(CLI::App& app) {
    auto* cmd = app.get_subcommand("calibrate");  // added by calibrate.cpp (order 50)
    auto a = std::make_shared<MicrogridCalibrationArgs>();
    auto& o = a->options;
    auto* mg = cmd->add_subcommand(
        "microgrid",
        "Microgrid (DoFP) camera: per-pixel NUC, analyzers and bad pixels from flat-field "
        "sessions");
    add_required_input(mg, "SESSION", o.sessions,
                       "Flat-field sessions of one microgrid camera: open blackbody at ≥ 2 "
                       "temperatures, a reference polarizer at ≥ 3 angles at ≥ 2 temperatures",
                       CLI::ExistingDirectory);
    add_output_option(mg, o.output,
                      "Per-pixel calibration EXR to write (for tirpol reduce --pixel-calibration)");
    add_band_options(mg, a->band_um, o.rsr)->capture_default_str();
    add_force_flag(mg, o.force);
    mg->callback([a] {
        a->options.band_um = {a->band_um[0], a->band_um[1]};
        print_text(calibration::microgrid_calibration_text(
            calibration::run_microgrid_calibration(a->options)));
    });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(58, register_calibrate_microgrid);

}  // namespace tirpol::cli
