#include <fmt/printf.h>

#include "tirpol/calibration/noise.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/output_guard.h"
#include "tirpol/core/utf8.h"

namespace tirpol::calibration {

NoiseAnalysis run_noise_analysis(const NoiseRunOptions& o) {
    OutputGuard()
        .input(o.stack, "STACK")
        .input(o.calibration, "--calibration")
        .output_file(o.output, "--output")
        .output_file(o.nedt_map, "--nedt-map")
        .check(o.force);
    const auto stack = load_frame_stack(o.stack, o.raw);
    std::optional<RadiometricCalibration> cal;
    if (!o.calibration.empty()) cal = read_radiometric_calibration(o.calibration);
    const NoiseAnalysis result = analyse_noise(stack, cal ? &*cal : nullptr, o.analysis);
    if (result.kelvin && !o.nedt_map.empty()) {
        Image map(stack.width, stack.height);
        map.set_channel("nedt_k", result.kelvin->nedt_k);
        map.set_channel("temporal_noise_counts", result.temporal_noise_counts);
        map.attributes()["units_nedt_k"] = std::string("K");
        write_exr(o.nedt_map, map);
    }
    write_file_atomic(o.output, json_text(noise_analysis_json(result, o.stack), 2) + "\n");
    return result;
}

std::string noise_analysis_text(const NoiseAnalysis& result, const std::string& output) {
    const char* convention = to_string(result.convention);
    std::string text;
    if (result.kelvin) {
        const auto& k = *result.kelvin;
        const auto& d3k = k.three_d_noise_k;
        text = fmt::sprintf(
            "NEDT median %.1f mK at %.2f K; 3D noise (mK, %s): σ_tvh %.1f, σ_vh %.1f, σ_t %.1f\n",
            1e3 * k.nedt_median_k, k.mean_brightness_temperature_k, convention, 1e3 * d3k.sigma_tvh,
            1e3 * d3k.sigma_vh, 1e3 * d3k.sigma_t);
    }
    const auto& d3 = result.three_d_noise_counts;
    return text + fmt::sprintf(
                      "%zu frames; 3D noise (counts, %s): σ_tvh %.3g, σ_vh %.3g, σ_v %.3g, σ_h "
                      "%.3g, σ_t %.3g, σ_tv %.3g, σ_th %.3g → %s\n",
                      result.frames, convention, d3.sigma_tvh, d3.sigma_vh, d3.sigma_v, d3.sigma_h,
                      d3.sigma_t, d3.sigma_tv, d3.sigma_th, output);
}

}  // namespace tirpol::calibration
