// `tirpol extract-emissivity`: polarized emissivity of regions of interest (paper eq 17) → CSV.

#include <cmath>
#include <cstdio>
#include <memory>

#include "cli.h"
#include "tirpol/calibration/calibration_chain.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"

namespace tirpol::cli {

namespace {
struct EmissivityArgs {
    std::string input, rois, output, calibration, polarimetric;
    std::vector<double> band_um;
    bool force = false;
};

bool same_band(const std::vector<double>& band_um, const Band& band) {
    return std::abs(band_um[0] - band.lo_um()) <= 1e-6 &&
           std::abs(band_um[1] - band.hi_um()) <= 1e-6;
}

void run_extract(const EmissivityArgs& a) {
    OutputGuard()
        .input(a.input, "INPUT")
        .input(a.rois, "ROIS")
        .input(a.calibration, "--calibration")
        .input(a.polarimetric, "--polarimetric")
        .output_file(a.output, "--output")
        .check(a.force);
    calibration::ChainInputs chain;
    calibration::ChainProducts given;
    if (std::filesystem::is_directory(a.input)) {
        if (a.calibration.empty())
            usage_error("--calibration", "{} is a session: CAL.exr is needed to reduce it",
                        a.input);
        given = calibration::read_calibration_products(a.calibration, a.polarimetric);
        chain.band = given.radiometric->band();
        if (!a.band_um.empty() && !same_band(a.band_um, chain.band))
            fail(
                "--band-um {:g} {:g} differs from the band of the radiometric calibration {} "
                "({:g}–{:g} µm) that "
                "reduces the session; leave --band-um out, or calibrate in that band",
                a.band_um[0], a.band_um[1], a.calibration, chain.band.lo_um(), chain.band.hi_um());
        chain.scene_sessions = {a.input};
    } else {
        given.stokes = {read_exr(a.input)};
        const auto& attributes = given.stokes.front().attributes();
        const auto it = attributes.find("band_um");
        if (!a.band_um.empty()) {
            chain.band = Band(a.band_um[0], a.band_um[1]);
            if (it != attributes.end() && std::holds_alternative<std::vector<double>>(it->second) &&
                std::get<std::vector<double>>(it->second).size() == 2 &&
                !same_band(std::get<std::vector<double>>(it->second), chain.band))
                fail(
                    "{}: its band_um ({:g}–{:g} µm) differs from --band-um {:g} {:g}; the Stokes "
                    "image's radiances "
                    "are in its own band: leave --band-um out",
                    a.input, std::get<std::vector<double>>(it->second)[0],
                    std::get<std::vector<double>>(it->second)[1], a.band_um[0], a.band_um[1]);
        } else if (it != attributes.end() &&
                   std::holds_alternative<std::vector<double>>(it->second) &&
                   std::get<std::vector<double>>(it->second).size() == 2) {
            const auto& b = std::get<std::vector<double>>(it->second);
            chain.band = Band(b[0], b[1]);
        } else {
            fail("{}: no band_um attribute; give --band-um LO HI", a.input);
        }
    }
    chain.rois = {calibration::EmissivityRois::load(a.rois)};
    const auto results =
        calibration::run_calibration_chain(chain, std::move(given)).emissivity.front();
    write_file_atomic(a.output, calibration::emissivity_csv(results));
    for (const auto& r : results)
        std::printf(
            "  %-16s θ=%5.1f°  ε_S0 = %.4f ± %.4f  ε_S1 = %+.4f ± %.4f  ε_S2 = %+.4f ± %.4f (2σ)\n",
            r.name.c_str(), r.view_angle_deg, r.eps_s0, 2.0 * r.eps_s0_std, r.eps_s1,
            2.0 * r.eps_s1_std, r.eps_s2, 2.0 * r.eps_s2_std);
    for (const auto& r : results)
        for (const auto& w : r.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    std::printf("written: %s\n", a.output.c_str());
}

void register_extract(CLI::App& app) {
    auto a = std::make_shared<EmissivityArgs>();
    auto* cmd = app.add_subcommand("extract-emissivity",
                                   "Polarized emissivity of regions (eq 17) → CSV for fitting");
    cmd->add_option("INPUT", a->input, "Stokes EXR from 'tirpol reduce', or a session directory")
        ->required()
        ->check(CLI::ExistingPath);
    cmd->add_option("ROIS", a->rois, "Regions YAML (reflector, targets)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("-o,--output", a->output, "CSV to write")->required();
    cmd->add_option("--calibration", a->calibration,
                    "Radiometric calibration EXR (INPUT is a session)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--polarimetric", a->polarimetric,
                    "Polarimetric calibration YAML (INPUT is a session)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--band-um", a->band_um, "Band LO HI (default: the Stokes EXR's band_um)")
        ->expected(2);
    add_force_flag(cmd, a->force);
    cmd->callback([a] { run_extract(*a); });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(56, register_extract);

}  // namespace tirpol::cli
