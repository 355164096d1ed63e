#pragma once
/// \file angle_statistics.h
/// Statistics of the angle of polarization (AoP) as an axial quantity: AoP and AoP + 180° are the
/// same state, so means and spreads are taken on the doubled angle (Mardia & Jupp, Directional
/// Statistics, 2000, §2.2 and §9.3.2: mean direction of axial data = half the mean of 2θ, circular
/// standard deviation √(−2 ln R̄)). Only pixels where both images are significantly polarized count:
/// elsewhere AoP is the angle of noise.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tirpol::report {

/// Linear polarization |P| = √(S1² + S2²) is significant when it exceeds this many σ of its noise.
inline constexpr double kAopSignificanceSigma = 3.0;

struct AopStats {
    std::size_t region_pixel_count = 0;  ///< pixels in the region with finite S1, S2 in both images
    std::size_t pixel_count = 0;         ///< of those, significantly polarized in both images
    double measured_mean_deg = 0.0;      ///< axial mean AoP, [0, 180)
    double simulated_mean_deg = 0.0;     ///< axial mean AoP, [0, 180)
    double difference_mean_deg = 0.0;    ///< axial mean of AoP_m − AoP_s, [−90, 90)
    double difference_std_deg = 0.0;     ///< circular standard deviation of AoP_m − AoP_s (axial)
};

/// The linear-polarization planes of one image, per pixel: S1, S2 and their variances.
struct LinearPolarizationPlanes {
    const std::vector<float>& s1;
    const std::vector<float>& s2;
    const std::vector<float>& var_s1;
    const std::vector<float>& var_s2;
};

/// AoP statistics over `mask` from the planes of both images. A pixel counts when
/// √(S1² + S2²) > kAopSignificanceSigma · √((var_S1 + var_S2)/2) in both the measured and the
/// simulated image. All planes have the mask's length.
AopStats aop_stats(const LinearPolarizationPlanes& measured,
                   const LinearPolarizationPlanes& simulated,
                   const std::vector<std::uint8_t>& mask);

}  // namespace tirpol::report
