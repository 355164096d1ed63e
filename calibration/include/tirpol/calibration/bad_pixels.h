#pragma once
/// \file bad_pixels.h
/// Bad-pixel classes, detection thresholds and the replacement rule. A pixel's class is a bit mask
/// stored as a float channel `bad` in the calibration EXR (0 = good).

#include <cstdint>
#include <vector>

namespace tirpol::calibration {

/// Bits of the bad-pixel mask.
enum BadPixel : std::uint32_t {
    kGood = 0,
    kDead = 1u << 0,       ///< responsivity (gain) below `dead_gain_fraction` × median gain
    kHot = 1u << 1,        ///< offset more than `hot_sigma` robust σ above the median offset
    kNoisy = 1u << 2,      ///< temporal noise above `noisy_factor` × median temporal noise
    kNonLinear = 1u << 3,  ///< fit residual more than `nonlinear_sigma` robust σ above the median
                           ///< and not explained by the pixel's temporal noise (fit quality ≥ 3)
    kSaturated = 1u << 4,  ///< at or above the saturation level in a calibration frame
    /// A microgrid pixel whose fitted analyzer is implausible: diattenuation or axis outside the
    /// limits of MicrogridFlatFieldOptions (a missing or damaged micro-polarizer).
    kBadAnalyzer = 1u << 5,
};

/// Thresholds of the detection (robust σ = 1.4826 × median absolute deviation).
struct BadPixelThresholds {
    double dead_gain_fraction = 0.25;
    double hot_sigma = 10.0;
    double noisy_factor = 3.0;
    double nonlinear_sigma = 10.0;
};

/// Median and robust σ (1.4826·MAD) of the finite values of `values`; {NaN, NaN} if none.
struct RobustStats {
    double median;
    double sigma;
};
RobustStats robust_stats(const std::vector<float>& values);

/// Replaces the values of bad pixels (mask ≠ 0) in `plane` (width × height) by the mean of the
/// good pixels in the 3×3 neighbourhood, widening to 5×5 and 7×7 when none is good; NaN if
/// still none. Replacement reads only good pixels, so the result does not depend on scan order.
void replace_bad_pixels(std::vector<float>& plane, const std::vector<float>& bad_mask, int width,
                        int height);

}  // namespace tirpol::calibration
