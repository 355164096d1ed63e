#include <algorithm>
#include <cmath>
#include <unsupported/Eigen/SpecialFunctions>

#include "tirpol/report/verdict.h"

namespace tirpol::report {

double TestDesign::false_alarm_per_quantity() const {
    const double q = static_cast<double>(std::max<std::size_t>(quantities_per_region, 1));
    return 1.0 - std::pow(1.0 - false_alarm_per_region, 1.0 / q);
}

UncertaintyComponent combine(const std::vector<UncertaintyComponent>& components) {
    double variance = 0.0, inverse_dof = 0.0;
    for (const auto& c : components) {
        const double v = c.sigma * c.sigma;
        variance += v;
        if (std::isfinite(c.dof) && v > 0.0) inverse_dof += v * v / c.dof;
    }
    UncertaintyComponent out;
    out.sigma = std::sqrt(variance);
    out.dof = inverse_dof > 0.0 ? variance * variance / inverse_dof : kInfiniteDof;
    return out;
}

UncertaintyComponent mean_of_independent(const std::vector<float>& variance,
                                         const std::vector<std::uint8_t>& valid,
                                         double dof_per_pixel) {
    double sum = 0.0, sum_squares = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < variance.size(); ++i) {
        if (!valid[i] || !std::isfinite(variance[i])) continue;
        const double v = std::max(0.0f, variance[i]);
        sum += v;
        sum_squares += v * v;
        ++n;
    }
    UncertaintyComponent out;
    if (n == 0) return out;
    out.sigma = std::sqrt(sum) / static_cast<double>(n);
    if (std::isfinite(dof_per_pixel) && sum_squares > 0.0)
        out.dof = sum * sum / (sum_squares / dof_per_pixel);
    return out;
}

double student_t_two_sided_tail(double t, double dof) {
    if (!std::isfinite(t)) return 0.0;
    if (!std::isfinite(dof)) return std::erfc(std::abs(t) / std::sqrt(2.0));
    // P(|T| > |t|) = I_{ν/(ν+t²)}(ν/2, ½) (Abramowitz & Stegun 26.7.1 with 26.5.27).
    return Eigen::numext::betainc(0.5 * dof, 0.5, dof / (dof + t * t));
}

double student_t_quantile(double p, double dof) {
    if (!(p > 0.0 && p < 1.0)) return std::numeric_limits<double>::quiet_NaN();
    if (!std::isfinite(dof)) return Eigen::numext::ndtri(p);
    if (p == 0.5) return 0.0;
    // Solve P(|T| > t) = 2 min(p, 1 − p) for t > 0 by bisection: the tail falls monotonically in t.
    const double tail = 2.0 * std::min(p, 1.0 - p);
    double lo = 0.0, hi = 1.0;
    while (student_t_two_sided_tail(hi, dof) > tail && hi < 1e12) hi *= 2.0;
    for (int i = 0; i < 200 && hi - lo > 1e-12 * hi; ++i) {
        const double mid = 0.5 * (lo + hi);
        (student_t_two_sided_tail(mid, dof) > tail ? lo : hi) = mid;
    }
    const double t = 0.5 * (lo + hi);
    return p < 0.5 ? -t : t;
}

MeanDifferenceTest test_mean_difference(const MeanDifferenceInputs& in, const TestDesign& design) {
    const auto& m = *in.measured;
    const auto& s = *in.simulated;
    const auto& mask = *in.mask;
    MeanDifferenceTest r;
    std::vector<std::uint8_t> valid(m.size(), 0);
    double sum = 0.0;
    for (std::size_t i = 0; i < m.size(); ++i) {
        if (!mask[i] || !std::isfinite(m[i]) || !std::isfinite(s[i])) continue;
        valid[i] = 1;
        sum += static_cast<double>(m[i]) - static_cast<double>(s[i]);
        ++r.pixel_count;
    }
    r.false_alarm = design.false_alarm_per_quantity();
    r.power = design.power;
    if (r.pixel_count == 0) return r;
    r.difference = sum / static_cast<double>(r.pixel_count);
    r.measured_independent = mean_of_independent(
        *in.measured_variance, valid, in.measured_variance_shared ? kInfiniteDof : in.measured_dof);
    if (in.measured_variance_shared) r.measured_independent.dof = in.measured_dof;
    r.simulated = mean_of_independent(*in.simulated_variance, valid, in.simulated_dof);
    r.measured_common = in.measured_common;
    r.registration = in.registration;
    r.combined = combine({r.measured_independent, r.measured_common, r.simulated, r.registration});
    r.critical_t = student_t_quantile(1.0 - 0.5 * r.false_alarm, r.combined.dof);
    r.detectable_bias =
        (r.critical_t + student_t_quantile(design.power, r.combined.dof)) * r.combined.sigma;
    if (!(r.combined.sigma > 0.0)) {
        // No stated noise at all: any difference exceeds it, none does not.
        r.t = r.difference == 0.0
                  ? 0.0
                  : std::copysign(std::numeric_limits<double>::infinity(), r.difference);
    } else {
        r.t = r.difference / r.combined.sigma;
    }
    r.p_value = student_t_two_sided_tail(r.t, r.combined.dof);
    r.verdict =
        std::abs(r.t) > r.critical_t ? Agreement::ExceedsNoise : Agreement::ConsistentWithNoise;
    return r;
}

SigmaDiagnostic sigma_diagnostic(const std::vector<float>& z,
                                 const std::vector<std::uint8_t>& mask) {
    SigmaDiagnostic d;
    double sum = 0.0;
    for (std::size_t i = 0; i < z.size(); ++i)
        if (mask[i] && std::isfinite(z[i])) {
            sum += z[i];
            ++d.pixel_count;
        }
    if (d.pixel_count < 3) return d;
    const double n = static_cast<double>(d.pixel_count), mean = sum / n;
    double centred = 0.0;
    for (std::size_t i = 0; i < z.size(); ++i)
        if (mask[i] && std::isfinite(z[i])) centred += (z[i] - mean) * (z[i] - mean);
    d.z_variance = centred / (n - 1.0);
    d.z_variance_sigma = std::sqrt(2.0 / (n - 1.0));
    d.sigma_factor = std::sqrt(d.z_variance);
    const bool significant = std::abs(d.z_variance - 1.0) > 3.0 * d.z_variance_sigma;
    if (significant && d.sigma_factor > kSigmaFactorTolerance)
        d.verdict = SigmaCheck::Underestimated;
    else if (significant && d.sigma_factor < 1.0 / kSigmaFactorTolerance)
        d.verdict = SigmaCheck::Overestimated;
    else
        d.verdict = SigmaCheck::Plausible;
    return d;
}

}  // namespace tirpol::report
