#pragma once
/// \file statistics.h
/// Per-region comparison statistics of a measured and a registered simulated quantity, and the
/// per-pixel normalised difference z = (m − s) / √(σ_m² + σ_s²): under the hypothesis that the
/// simulation is right and both noises are Gaussian, z ~ N(0, 1), so |z| > 2 in 4.55 % and |z| > 3
/// in 0.27 % of the pixels (two-sided normal tail probabilities, Abramowitz & Stegun 26.2).

#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace tirpol::report {

/// Two-sided tail probabilities of the standard normal distribution, P(|z| > 2) and P(|z| > 3)
/// (Abramowitz & Stegun, Handbook of Mathematical Functions, table 26.1: erfc(2/√2), erfc(3/√2)).
inline constexpr double kNormalTailAbove2 = 0.045500263896358;
inline constexpr double kNormalTailAbove3 = 0.002699796063260;

/// Statistics of one quantity over the pixels of a region where both values are finite.
/// std is the population standard deviation (divide by n); bias = mean(m − s);
/// rmse = √mean((m − s)²). All zero with pixel_count = 0 when no pixel is valid.
struct QuantityStats {
    std::size_t pixel_count = 0;
    double measured_mean = 0.0, measured_std = 0.0;
    double simulated_mean = 0.0, simulated_std = 0.0;
    double bias = 0.0, rmse = 0.0;
    /// Standard error of `bias`: sample std of m − s over √n (pixels treated as independent).
    double bias_sigma = 0.0;
};

/// `measured`, `simulated` and `mask` have the same length; a pixel counts when mask ≠ 0 and both
/// values are finite.
QuantityStats quantity_stats(const std::vector<float>& measured,
                             const std::vector<float>& simulated,
                             const std::vector<std::uint8_t>& mask);

/// Mean of the finite values of `data` under `mask`; nullopt when there is none.
std::optional<double> masked_mean(const std::vector<float>& data,
                                  const std::vector<std::uint8_t>& mask);

/// Per-pixel z = (m − s)/√(var_m + var_s); NaN where an input is not finite or the total variance
/// is not positive. A variance estimated from few samples (a Monte-Carlo render's per-pixel
/// variance has replicates − 1 degrees of freedom, its `variance_dof`) makes that ratio Student-t
/// distributed with heavier tails than a normal: with finite `measured_dof`/`simulated_dof` each z
/// is mapped to the normal value of the same two-sided tail probability under t with the
/// Welch–Satterthwaite degrees of freedom ν = (v_m + v_s)² / (v_m²/ν_m + v_s²/ν_s) (Welch 1947,
/// Biometrika 34, 28), so that |z| > 2 keeps meaning 4.55 % under noise alone. Infinite dof (the
/// default): the plain ratio.
std::vector<float> z_scores(const std::vector<float>& measured, const std::vector<float>& simulated,
                            const std::vector<float>& measured_variance,
                            const std::vector<float>& simulated_variance,
                            double measured_dof = std::numeric_limits<double>::infinity(),
                            double simulated_dof = std::numeric_limits<double>::infinity());

/// z_scores with a per-pixel `simulated_dof` (a variance pooled over each pixel's neighbourhood,
/// whose dof depends on the pixels pooled).
std::vector<float> z_scores(const std::vector<float>& measured, const std::vector<float>& simulated,
                            const std::vector<float>& measured_variance,
                            const std::vector<float>& simulated_variance, double measured_dof,
                            const std::vector<float>& simulated_dof);

/// The standard normal deviate with the same two-sided tail probability as `t` under Student's t
/// with `dof` degrees of freedom (sign kept); `t` itself for infinite dof.
double normal_equivalent_of_t(double t, double dof);

/// Summary of z over a region: fractions of valid pixels beyond 2 and 3, mean and RMS of z.
struct ZStats {
    std::size_t pixel_count = 0;
    double fraction_above_2 = 0.0, fraction_above_3 = 0.0;
    double mean = 0.0, rms = 0.0;
};
ZStats z_stats(const std::vector<float>& z, const std::vector<std::uint8_t>& mask);

/// True when the fraction of |z| > 2 does not exceed the normal expectation 4.55 % by more than
/// three binomial standard deviations √(p(1−p)/n): the differences are explained by the stated
/// noise. (Pixels are treated as independent; spatially correlated noise makes the test stricter
/// than it looks.)
bool consistent_with_noise(const ZStats& z);

/// Noise standard deviation of an image by Immerkær's method ("Fast noise variance estimation",
/// Computer Vision and Image Understanding 64(2), 1996, eq. 2): σ = √(π/2)/(6(W−2)(H−2)) Σ|I ∗ N|
/// with N the 3×3 difference of two Laplacians. Non-finite pixels and their neighbourhoods are
/// skipped.
double immerkaer_noise_sigma(const std::vector<float>& data, int width, int height);

}  // namespace tirpol::report
