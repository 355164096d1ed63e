#include "tirpol/calibration/noise.h"

namespace tirpol::calibration {

namespace {
nlohmann::json three_d_noise_json(const ThreeDNoise& d) {
    return {{"sigma_t", d.sigma_t},     {"sigma_v", d.sigma_v},        {"sigma_h", d.sigma_h},
            {"sigma_tv", d.sigma_tv},   {"sigma_th", d.sigma_th},      {"sigma_vh", d.sigma_vh},
            {"sigma_tvh", d.sigma_tvh}, {"sigma_total", d.sigma_total}};
}
}  // namespace

std::vector<float> kelvin_stack_responsivity(const RadiometricCalibration& cal) {
    std::vector<float> responsivity(cal.bad.size());
    for (std::size_t i = 0; i < responsivity.size(); ++i)
        responsivity[i] = cal.bad[i] == 0.0f ? 1.0f : 0.0f;
    return responsivity;
}

NoiseAnalysis analyse_noise(const FrameStack& stack, const RadiometricCalibration* cal,
                            const NoiseAnalysisOptions& options) {
    NoiseAnalysis a;
    a.frames = stack.frames.size();
    a.width = stack.width;
    a.height = stack.height;
    a.convention = options.convention;
    a.three_d_noise_counts = three_d_noise(stack, options.convention);
    a.temporal_noise_counts = temporal_noise(stack);
    a.temporal_noise_median_counts = finite_median(a.temporal_noise_counts);
    if (cal == nullptr) return a;
    // In kelvin after the calibration: the fixed pattern the calibration removes is gone, bad
    // pixels are replaced by their good neighbours (and left out of the NEDT statistics).
    const FrameStack kelvin = temperature_stack(stack, *cal, options.fpa_temperature_k);
    const std::vector<float> responsivity = kelvin_stack_responsivity(*cal);
    KelvinNoise k;
    k.three_d_noise_k = three_d_noise(kelvin, options.convention);
    k.mean_brightness_temperature_k = k.three_d_noise_k.mean;
    k.blackbody_temperature_k = options.blackbody_temperature_k.value_or(k.three_d_noise_k.mean);
    k.nedt_k = nedt_map(temporal_noise(kelvin), responsivity);
    k.nedt_median_k = finite_median(k.nedt_k);
    k.nedt_vs_frames_averaged = nedt_vs_averaging(kelvin, responsivity);
    a.kelvin = std::move(k);
    return a;
}

nlohmann::json noise_analysis_json(const NoiseAnalysis& a, const std::string& stack_source) {
    nlohmann::json out;
    out["stack"] = stack_source;
    out["frames"] = a.frames;
    out["width"] = a.width;
    out["height"] = a.height;
    out["units"] = "counts";
    out["convention"] = to_string(a.convention);
    out["mean_counts"] = a.three_d_noise_counts.mean;
    out["temporal_noise_median_counts"] = a.temporal_noise_median_counts;
    out["three_d_noise_counts"] = three_d_noise_json(a.three_d_noise_counts);
    if (a.kelvin) {
        const KelvinNoise& k = *a.kelvin;
        out["temperature_k"] = k.blackbody_temperature_k;
        out["mean_brightness_temperature_k"] = k.mean_brightness_temperature_k;
        out["nedt_median_k"] = k.nedt_median_k;
        out["three_d_noise_k"] = three_d_noise_json(k.three_d_noise_k);
        nlohmann::json curve = nlohmann::json::array();
        for (const auto& p : k.nedt_vs_frames_averaged)
            curve.push_back({{"frames_averaged", p.frames_averaged},
                             {"nedt_median_k", p.median_nedt_k},
                             {"white_noise_k", p.white_noise_k}});
        out["nedt_vs_frames_averaged"] = curve;
    }
    return out;
}

}  // namespace tirpol::calibration
