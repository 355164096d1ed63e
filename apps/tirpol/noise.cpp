// `tirpol noise`: temporal noise, NEDT and the 3D noise decomposition from a stack of frames of a
// uniform blackbody (docs/calibration.md).

#include <algorithm>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "tirpol/calibration/noise.h"
#include "tirpol/calibration/radiometric.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/utf8.h"

namespace tirpol::cli {

namespace {
struct NoiseArgs {
    std::string stack, output, calibration, nedt_map;
    std::optional<double> temperature_k;
};

/// A directory of single-frame EXRs (channel `counts`, sorted by name) or one EXR with channels frame_*.
calibration::FrameStack load_stack(const std::filesystem::path& path) {
    calibration::FrameStack stack;
    if (std::filesystem::is_directory(path)) {
        std::vector<std::filesystem::path> files;
        for (const auto& e : std::filesystem::directory_iterator(path))
            if (e.path().extension() == ".exr") files.push_back(e.path());
        std::sort(files.begin(), files.end());
        for (const auto& f : files) {
            const Image im = read_exr(f);
            if (stack.frames.empty()) {
                stack.width = im.width();
                stack.height = im.height();
            }
            if (im.width() != stack.width || im.height() != stack.height)
                fail("{}: frame is {}×{}, the first frame of the stack is {}×{}", f.string(), im.width(), im.height(),
                     stack.width, stack.height);
            stack.frames.push_back(im.channel("counts"));
        }
    } else {
        const Image im = read_exr(path);
        stack.width = im.width();
        stack.height = im.height();
        std::vector<std::string> names;
        for (const auto& n : im.channel_names())
            if (n.rfind("frame_", 0) == 0) names.push_back(n);
        std::sort(names.begin(), names.end());
        for (const auto& n : names) stack.frames.push_back(im.channel(n));
    }
    calibration::validate_stack(stack, path.c_str());
    return stack;
}

void run_noise(const NoiseArgs& a) {
    const auto stack = load_stack(a.stack);
    const auto d3 = calibration::three_d_noise(stack);
    const auto sigma = calibration::temporal_noise(stack);
    nlohmann::json out;
    out["stack"] = a.stack;
    out["frames"] = stack.frames.size();
    out["width"] = stack.width;
    out["height"] = stack.height;
    out["units"] = "counts";
    out["mean_counts"] = d3.mean;
    out["temporal_noise_median_counts"] = calibration::finite_median(sigma);
    out["three_d_noise_counts"] = {{"sigma_t", d3.sigma_t},   {"sigma_v", d3.sigma_v},   {"sigma_h", d3.sigma_h},
                                   {"sigma_tv", d3.sigma_tv}, {"sigma_th", d3.sigma_th}, {"sigma_vh", d3.sigma_vh},
                                   {"sigma_tvh", d3.sigma_tvh}, {"sigma_total", d3.sigma_total}};
    if (!a.calibration.empty()) {
        if (!a.temperature_k) fail("--calibration needs --temperature-k (the blackbody temperature of the stack)");
        const auto cal = calibration::read_radiometric_calibration(a.calibration);
        if (cal.width != stack.width || cal.height != stack.height)
            fail("{}: calibration is {}×{}, the stack {}×{}", a.calibration, cal.width, cal.height, stack.width, stack.height);
        const Band band = cal.band();
        const double l = band.radiance(*a.temperature_k), dl_dt = band.radiance_dT(*a.temperature_k);
        // Responsivity dcounts/dT = (g + 2qL)·dL/dT per pixel; bad pixels excluded.
        std::vector<float> responsivity(cal.gain.size());
        for (std::size_t i = 0; i < responsivity.size(); ++i) {
            const double q = cal.quadratic.empty() ? 0.0 : cal.quadratic[i];
            responsivity[i] = cal.bad[i] != 0.0f ? 0.0f : static_cast<float>((cal.gain[i] + 2.0 * q * l) * dl_dt);
        }
        const auto nedt = calibration::nedt_map(sigma, responsivity);
        const double median_resp = calibration::finite_median(responsivity);
        out["temperature_k"] = *a.temperature_k;
        out["median_responsivity_counts_per_k"] = median_resp;
        out["nedt_median_k"] = calibration::finite_median(nedt);
        nlohmann::json d3k;
        for (const auto& [k, v] : out["three_d_noise_counts"].items()) d3k[k] = v.get<double>() / median_resp;
        out["three_d_noise_k"] = d3k;
        nlohmann::json curve = nlohmann::json::array();
        for (const auto& p : calibration::nedt_vs_averaging(stack, responsivity))
            curve.push_back({{"frames_averaged", p.frames_averaged}, {"nedt_median_k", p.median_nedt_k},
                             {"white_noise_k", p.white_noise_k}});
        out["nedt_vs_frames_averaged"] = curve;
        if (!a.nedt_map.empty()) {
            Image map(stack.width, stack.height);
            map.set_channel("nedt_k", nedt);
            map.set_channel("temporal_noise_counts", sigma);
            map.attributes()["units_nedt_k"] = std::string("K");
            write_exr(a.nedt_map, map);
        }
        std::printf("NEDT median %.1f mK at %.2f K\n", 1e3 * out["nedt_median_k"].get<double>(), *a.temperature_k);
    }
    write_file_atomic(a.output, json_text(out, 2) + "\n");
    std::printf("3D noise (counts): σ_tvh %.3g, σ_vh %.3g, σ_v %.3g, σ_h %.3g, σ_t %.3g, σ_tv %.3g, σ_th %.3g → %s\n",
                d3.sigma_tvh, d3.sigma_vh, d3.sigma_v, d3.sigma_h, d3.sigma_t, d3.sigma_tv, d3.sigma_th, a.output.c_str());
}

void register_noise(CLI::App& app) {
    auto a = std::make_shared<NoiseArgs>();
    auto* cmd = app.add_subcommand("noise", "NEDT and 3D noise from a frame stack of a uniform blackbody");
    cmd->add_option("STACK", a->stack, "Directory of frame EXRs (channel counts) or one EXR with frame_* channels")
        ->required()
        ->check(CLI::ExistingPath);
    cmd->add_option("-o,--output", a->output, "Report JSON")->required();
    cmd->add_option("--calibration", a->calibration, "Radiometric calibration EXR (for NEDT in kelvin)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--temperature-k", a->temperature_k, "Blackbody temperature of the stack");
    cmd->add_option("--nedt-map", a->nedt_map, "Also write the per-pixel NEDT EXR here");
    cmd->callback([a] { run_noise(*a); });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(54, register_noise);

}  // namespace tirpol::cli
