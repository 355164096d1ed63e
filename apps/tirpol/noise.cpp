// `tirpol noise`: temporal noise, NEDT and the 3D noise decomposition from a stack of frames of a
// uniform blackbody (docs/calibration.md).

#include <cstdio>
#include <memory>

#include "cli.h"
#include "tirpol/calibration/frame_stack_io.h"
#include "tirpol/calibration/noise_report.h"
#include "tirpol/calibration/radiometric.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/utf8.h"

namespace tirpol::cli {

namespace {
struct NoiseArgs {
    std::string stack, output, calibration, nedt_map, convention = "sample", raw_type = "uint16";
    std::optional<double> temperature_k, fpa_temperature_k;
    std::vector<int> raw_shape;
    std::size_t raw_header_bytes = 0;
    bool force = false;
};

void run_noise(const NoiseArgs& a) {
    OutputGuard()
        .input(a.stack, "STACK")
        .input(a.calibration, "--calibration")
        .output_file(a.output, "--output")
        .output_file(a.nedt_map, "--nedt-map")
        .check(a.force);
    std::optional<calibration::RawFrameFormat> raw;
    if (!a.raw_shape.empty())
        raw = calibration::RawFrameFormat{a.raw_shape[0], a.raw_shape[1],
                                          calibration::raw_type_from_string(a.raw_type),
                                          a.raw_header_bytes};
    const auto stack = calibration::load_frame_stack(a.stack, raw);
    calibration::NoiseAnalysisOptions options;
    options.convention = a.convention == "sample" ? calibration::NoiseConvention::Sample
                                                  : calibration::NoiseConvention::Population;
    options.fpa_temperature_k = a.fpa_temperature_k;
    options.blackbody_temperature_k = a.temperature_k;
    std::optional<calibration::RadiometricCalibration> cal;
    if (!a.calibration.empty()) cal = calibration::read_radiometric_calibration(a.calibration);
    const auto result = calibration::analyse_noise(stack, cal ? &*cal : nullptr, options);
    const char* convention = calibration::to_string(result.convention);
    if (result.kelvin) {
        const auto& k = *result.kelvin;
        if (!a.nedt_map.empty()) {
            Image map(stack.width, stack.height);
            map.set_channel("nedt_k", k.nedt_k);
            map.set_channel("temporal_noise_counts", result.temporal_noise_counts);
            map.attributes()["units_nedt_k"] = std::string("K");
            write_exr(a.nedt_map, map);
        }
        const auto& d3k = k.three_d_noise_k;
        std::printf(
            "NEDT median %.1f mK at %.2f K; 3D noise (mK, %s): σ_tvh %.1f, σ_vh %.1f, σ_t %.1f\n",
            1e3 * k.nedt_median_k, k.mean_brightness_temperature_k, convention, 1e3 * d3k.sigma_tvh,
            1e3 * d3k.sigma_vh, 1e3 * d3k.sigma_t);
    }
    write_file_atomic(a.output,
                      json_text(calibration::noise_analysis_json(result, a.stack), 2) + "\n");
    const auto& d3 = result.three_d_noise_counts;
    std::printf(
        "%zu frames; 3D noise (counts, %s): σ_tvh %.3g, σ_vh %.3g, σ_v %.3g, σ_h %.3g, σ_t %.3g, "
        "σ_tv %.3g, "
        "σ_th %.3g → %s\n",
        result.frames, convention, d3.sigma_tvh, d3.sigma_vh, d3.sigma_v, d3.sigma_h, d3.sigma_t,
        d3.sigma_tv, d3.sigma_th, a.output.c_str());
}

void register_noise(CLI::App& app) {
    auto a = std::make_shared<NoiseArgs>();
    auto* cmd =
        app.add_subcommand("noise", "NEDT and 3D noise from a frame stack of a uniform blackbody");
    cmd->add_option("STACK", a->stack,
                    "Directory of frames (EXR channel counts, PNG, TIFF), one EXR with frame_* "
                    "channels, or a raw file "
                    "(--raw-shape)")
        ->required()
        ->check(CLI::ExistingPath);
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
    cmd->add_option("--fpa-temperature-k", a->fpa_temperature_k,
                    "Camera FPA temperature (FPA-dependent calibrations)");
    cmd->add_option("-o,--output", a->output, "Report JSON")->required();
    cmd->add_option("--calibration", a->calibration,
                    "Radiometric calibration EXR (for NEDT in kelvin)")
        ->check(CLI::ExistingFile);
    cmd->add_option(
        "--temperature-k", a->temperature_k,
        "Blackbody temperature of the stack, reported (default: the mean brightness temperature)");
    cmd->add_option("--nedt-map", a->nedt_map, "Also write the per-pixel NEDT EXR here");
    add_force_flag(cmd, a->force);
    cmd->callback([a] { run_noise(*a); });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(54, register_noise);

}  // namespace tirpol::cli
