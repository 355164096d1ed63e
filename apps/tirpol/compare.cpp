// `tirpol compare`: measured vs simulated Stokes images → a self-contained HTML report, report.json
// and PNGs (docs/report.md).

#include <memory>

#include "cli.h"
#include "common_options.h"
#include "invocation.h"
#include "tirpol/report/comparison_report.h"

namespace tirpol::cli {

namespace {

struct CompareArgs {
    report::ComparisonRunOptions options;
    bool json = false;
};

void run_compare(CompareArgs& a) {
    a.options.tool_version = version_text();
    a.options.command_line = command_line_text();
    const report::CompareResult r = report::run_comparison(a.options);
    print_text(a.json ? report::comparison_json(r) : report::comparison_text(r));
}

void register_compare(CLI::App& app) {
    auto args = std::make_shared<CompareArgs>();
    auto* cmd = app.add_subcommand(
        "compare", "Measured vs simulated Stokes images → HTML report with statistics");
    add_required_input(cmd, "--measured", args->options.measured,
                       "Measured Stokes EXR (from `tirpol reduce`)");
    add_required_input(cmd, "--simulated", args->options.simulated,
                       "Simulated Stokes EXR (from `tirpol render`)");
    cmd->add_option("--rois", args->options.regions,
                    "Regions of interest YAML (named polygons in measured pixels)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--control-points", args->options.control_points,
                    "Control points YAML (measured ↔ simulated pixels)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--camera", args->options.camera_model,
                    "The measured camera's model YAML (`tirpol calibrate geometric`) the "
                    "simulation was rendered through: "
                    "no warp, the residual misalignment is measured")
        ->check(CLI::ExistingFile);
    cmd->add_option("--registration", args->options.registration,
                    "none | auto | control-points | camera-model (default: camera-model with "
                    "--camera, else control-points if given, else auto)")
        ->check(CLI::IsMember({"none", "auto", "control-points", "camera-model"}));
    cmd->add_option("--measured-sigma", args->options.measured_frame_sigma,
                    "Radiance noise of one polarizer frame, W/(m²·sr), when the measured EXR has "
                    "no *_std channels");
    cmd->add_option(
        "--gain-sigma", args->options.gain_sigma_relative,
        "Relative calibration gain uncertainty common to every pixel (e.g. 0.005), default 0");
    cmd->add_option(
        "--offset-sigma", args->options.offset_sigma,
        "S0 calibration offset uncertainty common to every pixel, W/(m²·sr), default 0");
    cmd->add_option("--false-alarm", args->options.false_alarm,
                    "False-alarm probability per region (default 0.05)");
    cmd->add_option("--power", args->options.power,
                    "Power at which the detectable bias is quoted (default 0.80)");
    cmd->add_option("--band-um", args->options.band_um,
                    "Band LO HI in µm for the S0 bias in kelvin (default: the EXRs' band_um)")
        ->expected(2);
    cmd->add_option("-o,--output", args->options.output, "Report directory (created)")->required();
    cmd->add_flag("--json", args->json, "Print report.json to stdout instead of the summary");
    add_force_flag(cmd, args->options.force);
    cmd->callback([args] { run_compare(*args); });
}

}  // namespace

TIRPOL_REGISTER_COMMAND(700, register_compare);

}  // namespace tirpol::cli
