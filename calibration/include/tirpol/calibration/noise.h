#pragma once
/// \file noise.h
/// Sensor noise from a stack of frames of a uniform blackbody: per-pixel temporal noise, NEDT
/// (temporal noise / responsivity dS/dT), the 3D noise decomposition, and NEDT against the number
/// of frames averaged.
///
/// 3D noise (J. A. D'Agostino & C. M. Webb, "Three-dimensional analysis framework and measurement
/// methodology for imaging system noise", Proc. SPIE 1488, 110–121, 1991): the cube U(t, v, h)
/// (frame, row, column) is split with the directional averaging operators D_t, D_v, D_h into
/// U = S + N_t + N_v + N_h + N_tv + N_th + N_vh + N_tvh, e.g. N_t = D_vD_h U − S,
/// N_tv = D_h U − S − N_t − N_v, N_tvh = U − S − (all others). Each σ is the RMS of its component.
///
/// The counts → kelvin noise analysis of a frame stack of a uniform blackbody (`tirpol noise`,
/// docs/calibration.md, "Noise"): the 3D noise decomposition and temporal noise in counts and,
/// with a radiometric calibration, the same in kelvin with the NEDT map and NEDT against frames
/// averaged.
///
/// Frame stacks for `tirpol noise` from the files cameras and other tools write, and the same stack
/// in kelvin after a radiometric calibration (docs/calibration.md, "Noise").
///
/// `tirpol noise` from files to files: load a frame stack (and a radiometric calibration), analyse
/// it (analyse_noise), write the JSON report and the per-pixel NEDT map, and summarise as text.

#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/calibration/radiometric.h"

namespace tirpol::calibration {

/// A frame stack: `frames[t]` is one width × height frame (row-major).
struct FrameStack {
    int width = 0, height = 0;
    std::vector<std::vector<float>> frames;
};

/// The seven 3D-noise components (σ, units of the stack), their root-sum-square and the mean.
struct ThreeDNoise {
    double mean = 0.0;
    double sigma_t = 0.0;    ///< frame-to-frame (flicker)
    double sigma_v = 0.0;    ///< fixed row noise
    double sigma_h = 0.0;    ///< fixed column noise
    double sigma_tv = 0.0;   ///< temporal row noise (rain)
    double sigma_th = 0.0;   ///< temporal column noise
    double sigma_vh = 0.0;   ///< fixed-pattern (spatial) noise
    double sigma_tvh = 0.0;  ///< random spatio-temporal noise
    double sigma_total = 0.0;
};

/// How each component's σ is normalised. The components have zero mean by construction, so σ² is
/// Σx²/n (Population: D'Agostino & Webb; the seven variances add up exactly to the cube's variance)
/// or Σx²/(n − 1) (Sample: numpy std(ddof=1), as pyradi's ry3dnoise computes every component, e.g.
/// σ_t over the nt frame means, σ_vh over the nv·nh pixel means).
enum class NoiseConvention { Population, Sample };

/// "population (N)" or "sample (N-1, as pyradi ry3dnoise)".
const char* to_string(NoiseConvention convention);

/// Throws tirpol::Error for a stack with < 2 frames, frames of the wrong size or non-finite values.
void validate_stack(const FrameStack& stack, const char* source);

/// The 3D noise decomposition of the stack.
ThreeDNoise three_d_noise(const FrameStack& stack,
                          NoiseConvention convention = NoiseConvention::Population);

/// Per-pixel temporal standard deviation (n − 1 normalisation).
std::vector<float> temporal_noise(const FrameStack& stack);

/// Per-pixel NEDT = temporal σ / responsivity, responsivity in stack units per kelvin (e.g.
/// gain·dL/dT for counts); NaN where the responsivity is not positive.
std::vector<float> nedt_map(const std::vector<float>& temporal_sigma,
                            const std::vector<float>& responsivity_per_k);

/// One point of NEDT against frames averaged.
struct AveragingPoint {
    int frames_averaged = 1;
    double median_nedt_k = 0.0;  ///< measured: temporal σ of non-overlapping n-frame means
    double white_noise_k = 0.0;  ///< NEDT(1)/√n, what uncorrelated noise would give
};

/// NEDT(n) for n = 1, 2, 4, … while at least 4 independent n-frame means remain.
std::vector<AveragingPoint> nedt_vs_averaging(const FrameStack& stack,
                                              const std::vector<float>& responsivity_per_k);

/// Median of the finite values (NaN if none).
double finite_median(std::vector<float> values);

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

/// A headerless raw file of consecutive frames, row-major, little-endian (as pyradi's
/// ryfiles.readRawFrames reads them).
struct RawFrameFormat {
    enum class Type { UInt8, UInt16, Float32 };
    int width = 0, height = 0;
    Type type = Type::UInt16;
    std::size_t header_bytes = 0;  ///< skipped at the start of the file
};

/// Parses "uint8" | "uint16" | "float32"; throws tirpol::Error naming the accepted values.
RawFrameFormat::Type raw_type_from_string(const std::string& text);

/// Loads a stack from: a directory of frames (.exr with channel `counts`, 8/16-bit .png,
/// .tif/.tiff; sorted by name; all the same size), one EXR with channels frame_* (sorted by name),
/// or, when `raw` is given, a raw file whose size must be header_bytes + N·width·height·bytes per
/// value. Throws tirpol::Error naming the path for fewer than 2 frames, mixed sizes, a directory
/// with no frame file (listing the extensions looked for) or a raw file of the wrong size.
FrameStack load_frame_stack(const std::filesystem::path& path,
                            const std::optional<RawFrameFormat>& raw = std::nullopt);

/// The stack in kelvin: each frame through counts_to_radiance (bad pixels replaced by their good
/// neighbours, FPA-dependent calibrations at `fpa_temperature_k`), then to temperature to first
/// order about T₀, the brightness temperature of the stack's mean radiance:
/// T = T₀ + (L − L(T₀))/(dL/dT)(T₀) (for noise-sized deviations the second-order term is
/// ≈ 1e-4 of the deviation). Throws tirpol::Error for a size mismatch.
FrameStack temperature_stack(const FrameStack& counts, const RadiometricCalibration& cal,
                             std::optional<double> fpa_temperature_k = std::nullopt);

/// The stack (a directory, an EXR of frame_* channels, or a raw file with `raw`), the calibration
/// ("" = counts only), the analysis options and the files to write.
struct NoiseRunOptions {
    std::string stack;
    std::optional<RawFrameFormat> raw;
    std::string calibration;
    NoiseAnalysisOptions analysis;
    std::string output;    ///< report JSON (noise_analysis_json)
    std::string nedt_map;  ///< EXR nedt_k, temporal_noise_counts; "" = none (needs calibration)
    bool force = false;    ///< existing outputs may be replaced (OutputGuard)
};

/// Checks the outputs against the inputs (OutputGuard: OutputConflict before any work), loads,
/// analyses and writes the report (and the NEDT map when there is a calibration). Throws
/// tirpol::Error for a stack or calibration that does not read or does not fit.
NoiseAnalysis run_noise_analysis(const NoiseRunOptions& options);

/// The NEDT line (with a calibration) and the 3D-noise line in counts naming the report `output`.
std::string noise_analysis_text(const NoiseAnalysis& analysis, const std::string& output);

}  // namespace tirpol::calibration
