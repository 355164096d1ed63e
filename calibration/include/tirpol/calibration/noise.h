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

#include <vector>

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

}  // namespace tirpol::calibration
