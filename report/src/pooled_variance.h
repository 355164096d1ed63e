#pragma once
/// \file pooled_variance.h
/// A per-pixel variance estimated with few degrees of freedom (a render's S*_var: replicates − 1,
/// one at the default two replicates) is unbiased, but one pixel's estimate alone is too noisy to
/// divide by: the ratio (m − s)/√v̂ is Student-t with that many dof, |t₁| > 5 in 12.6 % of pixels.
/// Where the report shows a per-pixel value (the z maps, the σ diagnostic) it uses the mean of the
/// variances over the pixel's neighbourhood on the same surface instead, an unbiased estimate of
/// the local variance with ν_pixel × (pixels pooled) degrees of freedom (the pixels' Monte Carlo
/// errors are independent). The same pooling over a whole region is what the region-mean test does.

#include <vector>

namespace tirpol::report {

/// Below this per-pixel dof a variance is pooled before per-pixel use: ν ≥ 9 keeps |t_ν| > 5 under
/// 0.1 % (docs/simulation.md, "Why R = 2").
inline constexpr double kPerPixelVarianceDof = 9.0;
/// The neighbourhood: (2·radius + 1)² pixels, 25 (ν = 25 at one dof per pixel) away from edges.
inline constexpr int kVariancePoolRadiusPx = 2;

struct PooledVariance {
    std::vector<float> variance;  ///< mean of the neighbourhood's finite variances; NaN where none
    std::vector<float> dof;       ///< dof_per_pixel × the pixels pooled
};

/// Mean of `variance` (width × height, row-major) over the (2·radius_px + 1)² window around each
/// pixel, over the pixels whose values in every plane of `labels` (object_id, material_id: the
/// same surface) equal the centre's (NaN equals NaN) and whose variance is finite.
PooledVariance pool_variance(const std::vector<float>& variance,
                             const std::vector<const std::vector<float>*>& labels, int width,
                             int height, int radius_px, double dof_per_pixel);

}  // namespace tirpol::report
