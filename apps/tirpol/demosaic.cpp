// `tirpol demosaic`: one microgrid (division-of-focal-plane) frame → Stokes EXR (S0 S1 S2 DoLP
// AoP).

#include <cstdio>
#include <memory>
#include <optional>

#include "cli.h"
#include "tirpol/calibration/microgrid_file.h"
#include "tirpol/core/exr_io.h"

namespace tirpol::cli {

namespace {
struct DemosaicArgs {
    std::string input, output, pattern, method = "newton", channel = "counts";
    bool force = false;
};

void run_demosaic(const DemosaicArgs& a) {
    OutputGuard().input(a.input, "INPUT").output_file(a.output, "--output").check(a.force);
    std::optional<calibration::MicrogridPattern> pattern;
    if (!a.pattern.empty())
        pattern = parse_option_value(
            "--pattern", [&] { return calibration::MicrogridPattern::parse(a.pattern); });
    calibration::MicrogridReductionOptions options;
    options.method = parse_option_value(
        "--method", [&] { return calibration::parse_demosaic_method(a.method); });
    const calibration::MicrogridFileReduction r =
        calibration::reduce_microgrid_file(a.input, pattern, options, a.channel);
    write_exr(a.output, r.stokes);
    const auto s0 = channel_stats(r.stokes.channel("S0"));
    const auto dolp = channel_stats(r.stokes.channel("DoLP"));
    std::printf(
        "Stokes %d×%d (%s, pattern %s): S0 mean %.6g %s, DoLP mean %.4f; %d unrealizable pixel(s) "
        "projected → %s\n",
        r.stokes.width(), r.stokes.height(), a.method.c_str(), r.pattern.text().c_str(), s0.mean,
        r.units.c_str(), dolp.mean, r.unrealizable_pixels, a.output.c_str());
}

void register_demosaic(CLI::App& app) {
    auto a = std::make_shared<DemosaicArgs>();
    auto* cmd =
        app.add_subcommand("demosaic", "Microgrid (DoFP) frame → Stokes EXR (S0 S1 S2 DoLP AoP)");
    cmd->add_option("INPUT", a->input, "Microgrid frame: 16-bit PNG, TIFF or EXR")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option(
        "--pattern", a->pattern,
        "Analyzer angles of the 2×2 cell (0,0),(0,1),(1,0),(1,1) in degrees, e.g. 90,45,135,0, or "
        "'sony'; default: the pattern recorded in an EXR header");
    cmd->add_option("--method", a->method, "Demosaicing: super-pixel, bilinear or newton")
        ->capture_default_str();
    cmd->add_option("--channel", a->channel, "EXR channel holding the frame")
        ->capture_default_str();
    cmd->add_option("-o,--output", a->output, "Stokes EXR to write")->required();
    add_force_flag(cmd, a->force);
    cmd->callback([a] { run_demosaic(*a); });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(57, register_demosaic);

}  // namespace tirpol::cli
