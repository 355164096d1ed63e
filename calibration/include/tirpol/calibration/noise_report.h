#pragma once
/// \file noise_report.h
/// The counts → kelvin noise analysis of a frame stack of a uniform blackbody (`tirpol noise`,
/// docs/calibration.md, "Noise"): the 3D noise decomposition and temporal noise in counts and,
/// with a radiometric calibration, the same in kelvin with the NEDT map and NEDT against frames
/// averaged.

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/calibration/noise.h"
#include "tirpol/calibration/radiometric.h"

namespace tirpol::calibration {

/// How to analyse a stack.
struct NoiseAnalysisOptions {
    NoiseConvention convention = NoiseConvention::Sample;
    std::optional<double>
        fpa_temperature_k;  ///< camera FPA temperature (FPA-dependent calibrations)
    /// Blackbody temperature reported with the kelvin results (default: the mean brightness
    /// temperature of the stack).
    std::optional<double> blackbody_temperature_k;
};

/// The kelvin half of the analysis (needs a radiometric calibration).
struct KelvinNoise {
    double blackbody_temperature_k = 0.0;  ///< given, or the mean brightness temperature
    double mean_brightness_temperature_k = 0.0;
    ThreeDNoise three_d_noise_k;
    std::vector<float> nedt_k;  ///< per pixel; NaN at the calibration's bad pixels
    double nedt_median_k = 0.0;
    std::vector<AveragingPoint> nedt_vs_frames_averaged;
};

/// The analysis of one stack.
struct NoiseAnalysis {
    std::size_t frames = 0;
    int width = 0, height = 0;
    NoiseConvention convention = NoiseConvention::Sample;
    ThreeDNoise three_d_noise_counts;
    std::vector<float> temporal_noise_counts;  ///< per pixel
    double temporal_noise_median_counts = 0.0;
    std::optional<KelvinNoise> kelvin;  ///< set when a calibration was given
};

/// Responsivity of a stack already converted to kelvin (temperature_stack), for nedt_map: 1 K per
/// K at the calibration's good pixels, 0 at its bad ones, so they are left out of the NEDT
/// statistics (temperature_stack replaced them by their neighbours' values).
std::vector<float> kelvin_stack_responsivity(const RadiometricCalibration& cal);

/// Analyses `stack` (in counts); with `cal`, also in kelvin (temperature_stack). Throws
/// tirpol::Error for a stack the decomposition rejects or a calibration of another size.
NoiseAnalysis analyse_noise(const FrameStack& stack, const RadiometricCalibration* cal,
                            const NoiseAnalysisOptions& options = {});

/// The report `tirpol noise -o` writes: stack (the source named by the caller), frames, width,
/// height, units, convention, mean_counts, temporal_noise_median_counts, three_d_noise_counts and,
/// with a calibration, temperature_k, mean_brightness_temperature_k, nedt_median_k,
/// three_d_noise_k and nedt_vs_frames_averaged.
nlohmann::json noise_analysis_json(const NoiseAnalysis& analysis, const std::string& stack_source);

}  // namespace tirpol::calibration
