// `tirpol noise`: temporal noise, NEDT and the 3D noise decomposition from a stack of frames of a
// uniform blackbody (docs/calibration.md).

#include "tirpol/calibration/noise.h"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "tirpol/calibration/frame_stack_io.h"
#include "tirpol/calibration/radiometric.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
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

nlohmann::json to_json(const calibration::ThreeDNoise& d) {
    return {{"sigma_t", d.sigma_t},     {"sigma_v", d.sigma_v},        {"sigma_h", d.sigma_h},
            {"sigma_tv", d.sigma_tv},   {"sigma_th", d.sigma_th},      {"sigma_vh", d.sigma_vh},
            {"sigma_tvh", d.sigma_tvh}, {"sigma_total", d.sigma_total}};
}

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
    const auto convention = a.convention == "sample" ? calibration::NoiseConvention::Sample
                                                     : calibration::NoiseConvention::Population;
    const auto d3 = calibration::three_d_noise(stack, convention);
    const auto sigma = calibration::temporal_noise(stack);
    nlohmann::json out;
    out["stack"] = a.stack;
    out["frames"] = stack.frames.size();
    out["width"] = stack.width;
    out["height"] = stack.height;
    out["units"] = "counts";
    out["convention"] = calibration::to_string(convention);
    out["mean_counts"] = d3.mean;
    out["temporal_noise_median_counts"] = calibration::finite_median(sigma);
    out["three_d_noise_counts"] = to_json(d3);
    if (!a.calibration.empty()) {
        const auto cal = calibration::read_radiometric_calibration(a.calibration);
        // In kelvin after the calibration: the fixed pattern the calibration removes is gone, bad
        // pixels are replaced by their good neighbours (and left out of the NEDT statistics).
        const auto kelvin = calibration::temperature_stack(stack, cal, a.fpa_temperature_k);
        const auto d3k = calibration::three_d_noise(kelvin, convention);
        const auto sigma_k = calibration::temporal_noise(kelvin);
        std::vector<float> good(cal.bad.size());
        for (std::size_t i = 0; i < good.size(); ++i) good[i] = cal.bad[i] == 0.0f ? 1.0f : 0.0f;
        const auto nedt = calibration::nedt_map(sigma_k, good);
        const double t_k = a.temperature_k.value_or(d3k.mean);
        out["temperature_k"] = t_k;
        out["mean_brightness_temperature_k"] = d3k.mean;
        out["nedt_median_k"] = calibration::finite_median(nedt);
        out["three_d_noise_k"] = to_json(d3k);
        nlohmann::json curve = nlohmann::json::array();
        for (const auto& p : calibration::nedt_vs_averaging(kelvin, good))
            curve.push_back({{"frames_averaged", p.frames_averaged},
                             {"nedt_median_k", p.median_nedt_k},
                             {"white_noise_k", p.white_noise_k}});
        out["nedt_vs_frames_averaged"] = curve;
        if (!a.nedt_map.empty()) {
            Image map(stack.width, stack.height);
            map.set_channel("nedt_k", nedt);
            map.set_channel("temporal_noise_counts", sigma);
            map.attributes()["units_nedt_k"] = std::string("K");
            write_exr(a.nedt_map, map);
        }
        std::printf(
            "NEDT median %.1f mK at %.2f K; 3D noise (mK, %s): σ_tvh %.1f, σ_vh %.1f, σ_t %.1f\n",
            1e3 * out["nedt_median_k"].get<double>(), d3k.mean, calibration::to_string(convention),
            1e3 * d3k.sigma_tvh, 1e3 * d3k.sigma_vh, 1e3 * d3k.sigma_t);
    }
    write_file_atomic(a.output, json_text(out, 2) + "\n");
    std::printf(
        "%zu frames; 3D noise (counts, %s): σ_tvh %.3g, σ_vh %.3g, σ_v %.3g, σ_h %.3g, σ_t %.3g, "
        "σ_tv %.3g, "
        "σ_th %.3g → %s\n",
        stack.frames.size(), calibration::to_string(convention), d3.sigma_tvh, d3.sigma_vh,
        d3.sigma_v, d3.sigma_h, d3.sigma_t, d3.sigma_tv, d3.sigma_th, a.output.c_str());
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
