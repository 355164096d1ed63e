// `tirpol extract-emissivity`: polarized emissivity of regions of interest (paper eq 17) → CSV.

#include <cstdio>

#include "cli.h"
#include "common_options.h"
#include "tirpol/calibration/emissivity_extraction.h"

namespace tirpol::cli {

namespace {
struct ExtractArgs {
    calibration::EmissivityExtractionOptions options;
    std::vector<double> band_um;
};

void run_extract(ExtractArgs& a) {
    auto& o = a.options;
    if (!a.band_um.empty()) o.band_um = std::pair{a.band_um[0], a.band_um[1]};
    const auto results = calibration::extract_emissivity(o);
    print_text(calibration::emissivity_results_text(results));
    for (const auto& r : results)
        for (const auto& w : r.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    std::printf("written: %s\n", o.output.c_str());
}

void register_extract(CLI::App& app) {
    auto a = std::make_shared<ExtractArgs>();
    auto& o = a->options;
    auto* cmd = app.add_subcommand("extract-emissivity",
                                   "Polarized emissivity of regions (eq 17) → CSV for fitting");
    add_required_input(cmd, "INPUT", o.input,
                       "Stokes EXR from 'tirpol reduce', or a session directory",
                       CLI::ExistingPath);
    add_required_input(cmd, "ROIS", o.rois, "Regions YAML (reflector, targets)");
    add_output_option(cmd, o.output, "CSV to write");
    cmd->add_option("--calibration", o.calibration,
                    "Radiometric calibration EXR (INPUT is a session)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--polarimetric", o.polarimetric,
                    "Polarimetric calibration YAML (INPUT is a session)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--band-um", a->band_um, "Band LO HI (default: the Stokes EXR's band_um)")
        ->expected(2);
    add_force_flag(cmd, o.force);
    cmd->callback([a] { run_extract(*a); });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(56, register_extract);

}  // namespace tirpol::cli
