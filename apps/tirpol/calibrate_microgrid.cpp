// `tirpol calibrate microgrid`: a microgrid camera's per-pixel calibration (two-point NUC, each
// pixel's analyzer, bad pixels) from flat-field sessions (docs/microgrid.md).

#include <cstdio>
#include <memory>
#include <optional>

#include "cli.h"
#include "tirpol/calibration/microgrid_session.h"
#include "tirpol/core/exr_io.h"

namespace tirpol::cli {

namespace {
struct MicrogridCalibrationArgs {
    std::vector<std::string> sessions;
    std::string output, rsr;
    std::vector<double> band_um{8.0, 14.0};
    bool force = false;
};

void run_calibrate_microgrid(const MicrogridCalibrationArgs& a) {
    OutputGuard guard;
    for (const std::string& session : a.sessions) guard.input(session, "SESSION");
    guard.input(a.rsr, "--rsr").output_file(a.output, "--output").check(a.force);
    if (!(a.band_um[0] > 0.0 && a.band_um[1] > a.band_um[0]))
        usage_error("--band-um", "--band-um {} {}: expected 0 < LO < HI micrometres", a.band_um[0],
                    a.band_um[1]);
    std::optional<SpectralResponse> rsr;
    if (!a.rsr.empty()) rsr = SpectralResponse::load_csv(a.rsr);
    const Band band(a.band_um[0], a.band_um[1], rsr);
    const calibration::MicrogridFlatFieldCalibration result =
        calibration::calibrate_microgrid_sessions({a.sessions.begin(), a.sessions.end()}, band);
    const calibration::MicrogridPixelCalibration& cal = result.pixels;
    Image image = cal.to_image();
    image.attributes()["band_um"] = fmt::format("{} {}", a.band_um[0], a.band_um[1]);
    write_exr(a.output, image);
    std::printf("microgrid calibration %d×%d from %zu open-blackbody and %zu polarizer record(s)\n",
                cal.width, cal.height, result.open_blackbody_records, result.polarizer_records);
    std::printf("  two-point NUC: gain spread %.2f %%, fit RMS %.3g counts\n",
                100.0 * result.gain_rel_spread, result.nuc_fit_rms_counts);
    std::printf(
        "  analyzers: diattenuation median %.4f (robust σ %.4f), axis error RMS %.2f°, fit RMS "
        "%.3g counts\n",
        result.diattenuation_median, result.diattenuation_spread, result.axis_error_rms_deg,
        cal.fit_rms);
    std::printf(
        "  bad pixels: %zu (dead %zu, hot %zu, noisy %zu, non-linear %zu, saturated %zu, bad "
        "analyzer %zu)\n",
        result.bad_count(), result.bad_count(calibration::kDead),
        result.bad_count(calibration::kHot), result.bad_count(calibration::kNoisy),
        result.bad_count(calibration::kNonLinear), result.bad_count(calibration::kSaturated),
        result.bad_count(calibration::kBadAnalyzer));
    std::printf("→ %s\n", a.output.c_str());
}

void register_calibrate_microgrid(CLI::App& app) {
    auto* cmd = app.get_subcommand("calibrate");  // added by calibrate.cpp (order 50)
    auto a = std::make_shared<MicrogridCalibrationArgs>();
    auto* mg = cmd->add_subcommand(
        "microgrid",
        "Microgrid (DoFP) camera: per-pixel NUC, analyzers and bad pixels from flat-field "
        "sessions");
    mg->add_option("SESSION", a->sessions,
                   "Flat-field sessions of one microgrid camera: open blackbody at ≥ 2 "
                   "temperatures, a reference polarizer at ≥ 3 angles at ≥ 2 temperatures")
        ->required()
        ->check(CLI::ExistingDirectory);
    mg->add_option("-o,--output", a->output,
                   "Per-pixel calibration EXR to write (for tirpol reduce --pixel-calibration)")
        ->required();
    mg->add_option("--band-um", a->band_um, "Band limits LO HI in micrometres")
        ->expected(2)
        ->capture_default_str();
    mg->add_option("--rsr", a->rsr, "Relative spectral response CSV (wavelength_um,response)")
        ->check(CLI::ExistingFile);
    add_force_flag(mg, a->force);
    mg->callback([a] { run_calibrate_microgrid(*a); });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(58, register_calibrate_microgrid);

}  // namespace tirpol::cli
