// `tirpol demosaic`: one microgrid (division-of-focal-plane) frame → Stokes EXR (S0 S1 S2 DoLP
// AoP).

#include <memory>

#include "cli.h"
#include "common_options.h"
#include "tirpol/calibration/microgrid_run.h"

namespace tirpol::cli {

namespace {
void register_demosaic(CLI::App& app) {
    auto o = std::make_shared<calibration::DemosaicRunOptions>();
    auto* cmd =
        app.add_subcommand("demosaic", "Microgrid (DoFP) frame → Stokes EXR (S0 S1 S2 DoLP AoP)");
    add_required_input(cmd, "INPUT", o->input, "Microgrid frame: 16-bit PNG, TIFF or EXR");
    cmd->add_option(
        "--pattern", o->pattern,
        "Analyzer angles of the 2×2 cell (0,0),(0,1),(1,0),(1,1) in degrees, e.g. 90,45,135,0, or "
        "'sony'; default: the pattern recorded in an EXR header");
    cmd->add_option("--method", o->method, "Demosaicing: super-pixel, bilinear or newton")
        ->capture_default_str();
    cmd->add_option("--channel", o->channel, "EXR channel holding the frame")
        ->capture_default_str();
    cmd->add_option("-o,--output", o->output, "Stokes EXR to write")->required();
    add_force_flag(cmd, o->force);
    cmd->callback(
        [o] { print_text(calibration::demosaic_run_text(calibration::run_demosaic(*o))); });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(57, register_demosaic);

}  // namespace tirpol::cli
