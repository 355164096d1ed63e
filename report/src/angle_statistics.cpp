#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "tirpol/report/comparison_report.h"

namespace tirpol::report {

namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;

bool significant(float s1, float s2, float var_s1, float var_s2) {
    const double noise =
        std::sqrt(0.5 * (static_cast<double>(var_s1) + static_cast<double>(var_s2)));
    return std::hypot(static_cast<double>(s1), static_cast<double>(s2)) >
           kAopSignificanceSigma * noise;
}

// Axial mean in degrees in [lo, lo + 180) from the sum of unit phasors of the doubled angle.
double axial_mean_deg(std::complex<double> sum, double lo) {
    double a = 0.5 * std::arg(sum) * kDeg;
    while (a < lo) a += 180.0;
    while (a >= lo + 180.0) a -= 180.0;
    return a;
}

}  // namespace

AopStats aop_stats(const LinearPolarizationPlanes& measured,
                   const LinearPolarizationPlanes& simulated,
                   const std::vector<std::uint8_t>& mask) {
    AopStats st;
    // The phasor of the doubled AoP is (S1, S2)/|P|, so the angle itself is never formed and the
    // 0/180° wrap needs no special case.
    std::complex<double> sum_m, sum_s, sum_d;
    for (std::size_t i = 0; i < mask.size(); ++i) {
        if (!mask[i]) continue;
        const float m1 = measured.s1[i], m2 = measured.s2[i], s1 = simulated.s1[i],
                    s2 = simulated.s2[i];
        if (!std::isfinite(m1) || !std::isfinite(m2) || !std::isfinite(s1) || !std::isfinite(s2))
            continue;
        ++st.region_pixel_count;
        if (!significant(m1, m2, measured.var_s1[i], measured.var_s2[i]) ||
            !significant(s1, s2, simulated.var_s1[i], simulated.var_s2[i]))
            continue;
        const std::complex<double> pm(m1, m2), ps(s1, s2);
        const std::complex<double> um = pm / std::abs(pm), us = ps / std::abs(ps);
        sum_m += um;
        sum_s += us;
        sum_d += um * std::conj(us);  // phasor of 2(AoP_m − AoP_s)
        ++st.pixel_count;
    }
    if (st.pixel_count == 0) return st;
    st.measured_mean_deg = axial_mean_deg(sum_m, 0.0);
    st.simulated_mean_deg = axial_mean_deg(sum_s, 0.0);
    st.difference_mean_deg = axial_mean_deg(sum_d, -90.0);
    // Rounding can put R̄ a hair above 1 for identical angles.
    const double r = std::min(1.0, std::abs(sum_d) / static_cast<double>(st.pixel_count));
    // Circular std of the doubled angle, halved back to the axial angle.
    st.difference_std_deg = 0.5 * std::sqrt(-2.0 * std::log(std::max(r, 1e-300))) * kDeg;
    return st;
}

}  // namespace tirpol::report
