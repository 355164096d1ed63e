// `tirpol noise`: temporal noise, NEDT and the 3D noise decomposition from a stack of frames of a
// uniform blackbody (docs/calibration.md).

#include "tirpol/calibration/noise.h"

#include "cli.h"
#include "common_options.h"

namespace tirpol::cli {

namespace {
struct NoiseArgs {
    calibration::NoiseRunOptions options;
    std::string convention = "sample", raw_type = "uint16";
    std::vector<int> raw_shape;
    std::size_t raw_header_bytes = 0;
};

void run_noise(NoiseArgs& a) {
    auto& o = a.options;
    if (!a.raw_shape.empty())
        o.raw = calibration::RawFrameFormat{a.raw_shape[0], a.raw_shape[1],
                                            calibration::raw_type_from_string(a.raw_type),
                                            a.raw_header_bytes};
    o.analysis.convention = a.convention == "sample" ? calibration::NoiseConvention::Sample
                                                     : calibration::NoiseConvention::Population;
    print_text(calibration::noise_analysis_text(calibration::run_noise_analysis(o), o.output));
}

void register_noise(CLI::App& app) {
    auto a = std::make_shared<NoiseArgs>();
    auto& o = a->options;
    auto* cmd =
        app.add_subcommand("noise", "NEDT and 3D noise from a frame stack of a uniform blackbody");
    add_required_input(cmd, "STACK", o.stack,
                       "Directory of frames (EXR channel counts, PNG, TIFF), one EXR with frame_* "
                       "channels, or a raw file (--raw-shape)",
                       CLI::ExistingPath);
    cmd->add_option("--raw-shape", a->raw_shape,
                    "STACK is a headerless raw file of frames WIDTH HEIGHT")
        ->expected(2);
    cmd->add_option("--raw-type", a->raw_type,
                    "Raw value type: uint8, uint16, float32 (little-endian)")
        ->check(CLI::IsMember({"uint8", "uint16", "float32"}))
        ->capture_default_str();
    cmd->add_option("--raw-header-bytes", a->raw_header_bytes,
                    "Bytes to skip at the start of the raw file");
    cmd->add_option("--convention", a->convention,
                    "3D-noise σ normalisation: sample (N-1, as pyradi ry3dnoise) or population (N, "
                    "D'Agostino & Webb)")
        ->check(CLI::IsMember({"sample", "population"}))
        ->capture_default_str();
    cmd->add_option("--fpa-temperature-k", o.analysis.fpa_temperature_k,
                    "Camera FPA temperature (FPA-dependent calibrations)");
    add_output_option(cmd, o.output, "Report JSON");
    cmd->add_option("--calibration", o.calibration,
                    "Radiometric calibration EXR (for NEDT in kelvin)")
        ->check(CLI::ExistingFile);
    cmd->add_option(
        "--temperature-k", o.analysis.blackbody_temperature_k,
        "Blackbody temperature of the stack, reported (default: the mean brightness temperature)");
    cmd->add_option("--nedt-map", o.nedt_map, "Also write the per-pixel NEDT EXR here");
    add_force_flag(cmd, o.force);
    cmd->callback([a] { run_noise(*a); });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(54, register_noise);

}  // namespace tirpol::cli
