#pragma once
/// \file pooled_variance.h
/// A per-pixel variance estimated with few degrees of freedom (a render's S*_var: replicates − 1,
/// one at the default two replicates) is unbiased, but one pixel's estimate alone is too noisy to
/// divide by: the ratio (m − s)/√v̂ is Student-t with that many dof, |t₁| > 5 in 12.6 % of pixels.
/// Where the report shows a per-pixel value (the z maps, the σ diagnostic) it uses the mean of the
/// variances over the pixel's neighbourhood on the same surface instead, an unbiased estimate of
/// the neighbourhood's mean variance. Its degrees of freedom are Satterthwaite's (Biometrics Bull.
/// 2(6), 1946): ν·(Σσ²)²/Σσ⁴ over the n pixels pooled, ν·n only where their variances are equal;
/// the pixels' Monte Carlo errors are independent (their own random numbers), so no covariance term
/// enters. The same pooling over a whole region is what the region-mean test does.

#include <vector>

namespace tirpol::report {

/// Below this per-pixel dof a variance is pooled before per-pixel use: ν ≥ 9 keeps |t_ν| > 5 under
/// 0.1 % (docs/simulation.md, "Why R = 2").
inline constexpr double kPerPixelVarianceDof = 9.0;
/// The neighbourhood: (2·radius + 1)² pixels, 25 (ν = 25 at one dof per pixel) away from edges.
inline constexpr int kVariancePoolRadiusPx = 2;

struct PooledVariance {
    std::vector<float> variance;  ///< mean of the neighbourhood's finite variances; NaN where none
    /// Satterthwaite's effective dof of that mean, from the pooled estimates themselves
    /// (satterthwaite_pooled_dof); 0 where none.
    std::vector<float> dof;
};

/// Effective degrees of freedom of the mean of n = `count` independent variance estimates v̂ⱼ of
/// `dof_per_pixel` = ν each, given Σv̂ⱼ and Σv̂ⱼ². Satterthwaite's ν·(Σσ²)²/Σσ⁴ with each moment
/// replaced by its unbiased estimate (E v̂² = σ⁴·(ν + 2)/ν, E(Σv̂)² = (Σσ²)² + (2/ν)·Σσ⁴):
/// (ν + 2)·(Σv̂)²/Σv̂² − 2, held to [ν, ν·n] (one pixel's dof at least, the equal-variance value at
/// most); ν·n when every v̂ is 0. With one dof per pixel a single bright pixel's variance is rarely
/// seen in its own estimate (the median of χ²₁ is 0.45 of its mean), so where one pixel's variance
/// stands far above its neighbours' the result stays above the true value (docs/report.md).
double satterthwaite_pooled_dof(double sum, double sum_of_squares, int count, double dof_per_pixel);

/// Mean of `variance` (width × height, row-major) over the (2·radius_px + 1)² window around each
/// pixel, over the pixels whose values in every plane of `labels` (object_id, material_id: the
/// same surface) equal the centre's (NaN equals NaN) and whose variance is finite.
PooledVariance pool_variance(const std::vector<float>& variance,
                             const std::vector<const std::vector<float>*>& labels, int width,
                             int height, int radius_px, double dof_per_pixel);

}  // namespace tirpol::report
