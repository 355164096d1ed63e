#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <unsupported/Eigen/SpecialFunctions>

#include "tirpol/report/comparison_report.h"

namespace tirpol::report {

QuantityStats quantity_stats(const std::vector<float>& measured,
                             const std::vector<float>& simulated,
                             const std::vector<std::uint8_t>& mask) {
    // Two passes (means, then centred sums) so that large offsets like S0 ≈ 30 W/(m²·sr) with
    // millikelvin-level differences do not lose precision.
    QuantityStats st;
    double sum_m = 0.0, sum_s = 0.0;
    for (std::size_t i = 0; i < measured.size(); ++i) {
        if (!mask[i] || !std::isfinite(measured[i]) || !std::isfinite(simulated[i])) continue;
        sum_m += measured[i];
        sum_s += simulated[i];
        ++st.pixel_count;
    }
    if (st.pixel_count == 0) return st;
    const double n = static_cast<double>(st.pixel_count);
    st.measured_mean = sum_m / n;
    st.simulated_mean = sum_s / n;
    double var_m = 0.0, var_s = 0.0, sum_d = 0.0, sum_d2 = 0.0;
    for (std::size_t i = 0; i < measured.size(); ++i) {
        if (!mask[i] || !std::isfinite(measured[i]) || !std::isfinite(simulated[i])) continue;
        const double dm = measured[i] - st.measured_mean, ds = simulated[i] - st.simulated_mean;
        const double d = static_cast<double>(measured[i]) - static_cast<double>(simulated[i]);
        var_m += dm * dm;
        var_s += ds * ds;
        sum_d += d;
        sum_d2 += d * d;
    }
    st.measured_std = std::sqrt(var_m / n);
    st.simulated_std = std::sqrt(var_s / n);
    st.bias = sum_d / n;
    st.rmse = std::sqrt(sum_d2 / n);
    if (st.pixel_count > 1)
        st.bias_sigma = std::sqrt(std::max(0.0, sum_d2 - n * st.bias * st.bias) / (n - 1.0) / n);
    return st;
}

std::optional<double> masked_mean(const std::vector<float>& data,
                                  const std::vector<std::uint8_t>& mask) {
    double sum = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < data.size(); ++i)
        if (mask[i] && std::isfinite(data[i])) {
            sum += data[i];
            ++n;
        }
    if (n == 0) return std::nullopt;
    return sum / static_cast<double>(n);
}

double normal_equivalent_of_t(double t, double dof) {
    if (!std::isfinite(dof) || !std::isfinite(t) || t == 0.0) return t;
    // P(|T| > |t|) = I_{ν/(ν+t²)}(ν/2, ½) (Abramowitz & Stegun 26.7.1 with 26.5.27).
    const double tail = Eigen::numext::betainc(0.5 * dof, 0.5, dof / (dof + t * t));
    if (!(tail > 0.0)) return t;  // beyond double precision: as extreme as the ratio says
    return std::copysign(-Eigen::numext::ndtri(0.5 * tail), t);
}

namespace {

/// One pixel's normal-equivalent z; NaN where an input is not finite or the variance not positive.
float z_score(float measured, float simulated, double vm, double vs, double measured_dof,
              double simulated_dof) {
    const double var = vm + vs;
    if (!std::isfinite(measured) || !std::isfinite(simulated) || !std::isfinite(var) ||
        !(var > 0.0))
        return std::numeric_limits<float>::quiet_NaN();
    const double ratio =
        (static_cast<double>(measured) - static_cast<double>(simulated)) / std::sqrt(var);
    const double inverse_dof =
        vm * vm / measured_dof + vs * vs / simulated_dof;  // 0 for infinite dof
    return static_cast<float>(
        inverse_dof > 0.0 ? normal_equivalent_of_t(ratio, var * var / inverse_dof) : ratio);
}

}  // namespace

std::vector<float> z_scores(const std::vector<float>& measured, const std::vector<float>& simulated,
                            const std::vector<float>& measured_variance,
                            const std::vector<float>& simulated_variance, double measured_dof,
                            double simulated_dof) {
    std::vector<float> z(measured.size());
    for (std::size_t i = 0; i < measured.size(); ++i)
        z[i] = z_score(measured[i], simulated[i], measured_variance[i], simulated_variance[i],
                       measured_dof, simulated_dof);
    return z;
}

std::vector<float> z_scores(const std::vector<float>& measured, const std::vector<float>& simulated,
                            const std::vector<float>& measured_variance,
                            const std::vector<float>& simulated_variance, double measured_dof,
                            const std::vector<float>& simulated_dof) {
    std::vector<float> z(measured.size());
    for (std::size_t i = 0; i < measured.size(); ++i)
        z[i] = z_score(measured[i], simulated[i], measured_variance[i], simulated_variance[i],
                       measured_dof, simulated_dof[i]);
    return z;
}

ZStats z_stats(const std::vector<float>& z, const std::vector<std::uint8_t>& mask) {
    ZStats st;
    std::size_t above2 = 0, above3 = 0;
    double sum = 0.0, sum2 = 0.0;
    for (std::size_t i = 0; i < z.size(); ++i) {
        if (!mask[i] || !std::isfinite(z[i])) continue;
        const double v = z[i];
        ++st.pixel_count;
        above2 += std::abs(v) > 2.0;
        above3 += std::abs(v) > 3.0;
        sum += v;
        sum2 += v * v;
    }
    if (st.pixel_count == 0) return st;
    const double n = static_cast<double>(st.pixel_count);
    st.fraction_above_2 = static_cast<double>(above2) / n;
    st.fraction_above_3 = static_cast<double>(above3) / n;
    st.mean = sum / n;
    st.rms = std::sqrt(sum2 / n);
    return st;
}

bool consistent_with_noise(const ZStats& z) {
    if (z.pixel_count == 0) return true;
    const double p = kNormalTailAbove2;
    return z.fraction_above_2 <=
           p + 3.0 * std::sqrt(p * (1.0 - p) / static_cast<double>(z.pixel_count));
}

double immerkaer_noise_sigma(const std::vector<float>& data, int width, int height) {
    static constexpr int kKernel[3][3] = {{1, -2, 1}, {-2, 4, -2}, {1, -2, 1}};
    double sum = 0.0;
    std::size_t n = 0;
    for (int y = 1; y + 1 < height; ++y)
        for (int x = 1; x + 1 < width; ++x) {
            double acc = 0.0;
            bool finite = true;
            for (int dy = -1; dy <= 1 && finite; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const float v =
                        data[static_cast<std::size_t>(y + dy) * static_cast<std::size_t>(width) +
                             static_cast<std::size_t>(x + dx)];
                    if (!std::isfinite(v)) {
                        finite = false;
                        break;
                    }
                    acc += kKernel[dy + 1][dx + 1] * static_cast<double>(v);
                }
            if (!finite) continue;
            sum += std::abs(acc);
            ++n;
        }
    if (n == 0) return 0.0;
    return std::sqrt(std::numbers::pi / 2.0) * sum / (6.0 * static_cast<double>(n));
}

}  // namespace tirpol::report
