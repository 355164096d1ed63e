#pragma once
/// \file verdict.h
/// A region's verdict on one quantity, in two separate parts: the agreement (is the region-mean
/// difference within the noise of both sides, with the bias the test could have detected) and the
/// σ diagnostic (is the stated per-pixel σ plausible, from the scatter of z). A region's agreement
/// is "exceeds noise" when any of S0, S1, S2 exceeds it; each quantity is tested at the Šidák level
/// that keeps the region's false-alarm rate at the design's.
///
/// Does a region's mean measured − simulated difference exceed what the noise of both sides allows,
/// and how large a difference could the test have seen? The region mean's standard uncertainty
/// holds the parts that are independent from pixel to pixel (temporal noise of the measurement, the
/// render's Monte Carlo noise: they average down as 1/√n) and the parts that are common to every
/// pixel of the region (calibration gain/offset errors, registration: they do not). Its degrees of
/// freedom follow Welch–Satterthwaite (Welch 1947, Biometrika 34, 28; GUM JCGM 100:2008 eq G.2b),
/// and the test uses Student-t quantiles, so a variance estimated from few samples (a render's
/// `variance_dof`) neither false-alarms nor hides a bias. Separately, the per-pixel scatter of z
/// tells whether the stated per-pixel σ is plausible (a diagnostic, not the agreement verdict).

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace tirpol::report {

inline constexpr double kInfiniteDof = std::numeric_limits<double>::infinity();

/// The test's design: false-alarm probability per region (over its quantities together) and the
/// power at which the detectable bias is quoted.
struct TestDesign {
    double false_alarm_per_region = 0.05;
    double power = 0.80;
    std::size_t quantities_per_region = 3;  ///< S0, S1, S2: each is tested at the Šidák level below
    /// Per-quantity level α_q = 1 − (1 − α)^(1/quantities), so that a region with every quantity
    /// consistent false-alarms with probability `false_alarm_per_region` (independent quantities).
    double false_alarm_per_quantity() const;
};

/// One standard uncertainty (same units as the difference) with its degrees of freedom (∞: exact or
/// type B without stated reliability).
struct UncertaintyComponent {
    double sigma = 0.0;
    double dof = kInfiniteDof;
};

/// √(Σσ²) of independent components with the Welch–Satterthwaite dof ν = σ⁴ / Σ(σ_i⁴/ν_i).
UncertaintyComponent combine(const std::vector<UncertaintyComponent>& components);

/// Standard uncertainty of the mean over the masked, finite pixels of a quantity whose per-pixel
/// variances `variance` are independent from pixel to pixel, each estimated with `dof_per_pixel`:
/// σ = √(Σ v_i)/n, ν = (Σ v_i)² / Σ(v_i²/ν_pixel) (n·ν_pixel for equal variances). `valid` selects
/// the pixels (mask ≠ 0).
UncertaintyComponent mean_of_independent(const std::vector<float>& variance,
                                         const std::vector<std::uint8_t>& valid,
                                         double dof_per_pixel);

/// Quantile t_p of Student's t with `dof` degrees of freedom (the standard normal's for infinite
/// dof), 0 < p < 1; from the regularised incomplete beta function (Abramowitz & Stegun 26.7.1) by
/// bisection.
double student_t_quantile(double p, double dof);

/// Two-sided tail probability P(|T_ν| > |t|).
double student_t_two_sided_tail(double t, double dof);

enum class Agreement {
    NoData,               ///< no pixel where both images are finite
    ConsistentWithNoise,  ///< |mean difference| ≤ t_{1−α_q/2,ν} σ_mean
    ExceedsNoise,         ///< |mean difference| > t_{1−α_q/2,ν} σ_mean
};

/// The region-mean test of one quantity.
struct MeanDifferenceTest {
    std::size_t pixel_count = 0;
    double difference = 0.0;  ///< mean(m − s) over the pixels, units of the quantity
    UncertaintyComponent measured_independent;  ///< temporal noise etc. (the measured σ channels)
    UncertaintyComponent measured_common;  ///< calibration errors common to the region (type B)
    UncertaintyComponent simulated;        ///< Monte Carlo noise of the render (its *_var channels)
    UncertaintyComponent registration;  ///< residual misalignment × the region's mean S gradient
    UncertaintyComponent combined;      ///< all four, Welch–Satterthwaite dof
    double t = 0.0;                     ///< difference / combined σ
    double p_value = 1.0;               ///< two-sided, Student t with the combined dof
    double critical_t = 0.0;            ///< t_{1−α_q/2, ν}
    double false_alarm = 0.0;           ///< α_q used
    double power = 0.0;                 ///< the design's power
    /// Smallest |bias| detected with probability `power` at false-alarm α_q:
    /// (t_{1−α_q/2,ν} + t_{power,ν})·σ_mean (the usual normal-approximation power formula with t
    /// quantiles).
    double detectable_bias = 0.0;
    Agreement verdict = Agreement::NoData;
};

/// Inputs of the region-mean test of one quantity over one region (all planes the same length).
struct MeanDifferenceInputs {
    const std::vector<float>* measured = nullptr;
    const std::vector<float>* simulated = nullptr;
    const std::vector<float>* measured_variance = nullptr;   ///< per pixel, independent
    const std::vector<float>* simulated_variance = nullptr;  ///< per pixel, independent
    const std::vector<std::uint8_t>* mask = nullptr;
    double measured_dof = kInfiniteDof, simulated_dof = kInfiniteDof;  ///< per pixel
    /// The measured variance is one estimate shared by every pixel (the scatter of a flat region):
    /// its errors do not average over the region, so the mean's dof is `measured_dof` itself.
    bool measured_variance_shared = false;
    UncertaintyComponent
        measured_common;  ///< σ of the region mean common to all pixels (calibration)
    UncertaintyComponent registration;  ///< σ of the region mean from the registration
};

MeanDifferenceTest test_mean_difference(const MeanDifferenceInputs& in, const TestDesign& design);

enum class SigmaCheck {
    NoData,          ///< fewer than 3 pixels with a z
    Plausible,       ///< the scatter of z is that of a standard normal within its sampling error
    Overestimated,   ///< z scatters less: the stated per-pixel σ is too large
    Underestimated,  ///< z scatters more: the stated per-pixel σ is too small, or the difference
                     ///< varies in the region
};

/// Per-pixel σ factor beyond which a significant departure is reported (σ wrong by 25 % or more).
inline constexpr double kSigmaFactorTolerance = 1.25;

/// The scatter of z over a region: its sample variance (about its own mean, so a uniform bias does
/// not count) against 1, the variance of a standard normal, whose sampling standard deviation for n
/// values is √(2/(n − 1)). z is the normal-equivalent z of `z_scores`, which is standard normal
/// under the null at any dof.
struct SigmaDiagnostic {
    std::size_t pixel_count = 0;
    double z_variance = 0.0;        ///< sample variance of z
    double z_variance_sigma = 0.0;  ///< √(2/(n − 1)): its expected scatter under the null
    double sigma_factor =
        1.0;  ///< √(z_variance): the stated σ is this many times too small (> 1) or too large (< 1)
    SigmaCheck verdict = SigmaCheck::NoData;
};

/// Overestimated/Underestimated when z_variance is more than 3 of its sampling σ from 1 and the σ
/// factor lies outside [1/kSigmaFactorTolerance, kSigmaFactorTolerance].
SigmaDiagnostic sigma_diagnostic(const std::vector<float>& z,
                                 const std::vector<std::uint8_t>& mask);

/// The verdict of one quantity in one region.
struct QuantityVerdict {
    MeanDifferenceTest mean;  ///< the agreement test of the region mean
    SigmaDiagnostic sigma;    ///< the plausibility of the per-pixel σ
};

/// The worse of two agreements (ExceedsNoise > ConsistentWithNoise > NoData).
Agreement worse(Agreement a, Agreement b);

/// "no data", "consistent with noise", "exceeds noise".
std::string to_string(Agreement agreement);

/// "no data", "σ plausible", "σ overestimated", "σ underestimated".
std::string to_string(SigmaCheck check);

/// One sentence on the agreement, e.g. "mean difference −0.012 ± 0.004 (t = −3.0, ν = 812, p =
/// 0.003; detectable bias 0.013 at 1.7 % false alarm, 80 % power)".
std::string explain(const MeanDifferenceTest& test);

/// One sentence on the σ diagnostic, e.g. "z scatters with σ 0.45 (expected 1 ± 0.05): the stated σ
/// is about 2.2× too large".
std::string explain(const SigmaDiagnostic& diagnostic);

}  // namespace tirpol::report
