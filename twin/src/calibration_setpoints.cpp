#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "tirpol/core/error.h"
#include "tirpol/twin/twin.h"

namespace tirpol::twin {

namespace {

struct Clamped {
    double k;
    bool clamped;
};

Clamped clamp_to_laboratory(double k) {
    const double c = std::clamp(k, kColdestBlackbodyK, kWarmestBlackbodyK);
    return {c, c != k};
}

}  // namespace

BlackbodySetpoints blackbody_setpoints(const std::vector<Image>& truth,
                                       const simulation::SensorModel& sensor, const Band& band) {
    const double tau = sensor.analyzer.transmission;
    const double tau_min = tau / sensor.analyzer.extinction_ratio;
    const double background =
        sensor.background.reflectance * sensor.background.reflected_radiance +
        sensor.background.emissivity * band.radiance(sensor.background.temperature_k);
    BlackbodySetpoints out;
    double s0_lo = std::numeric_limits<double>::infinity(), s0_hi = -s0_lo, det_lo = s0_lo,
           det_hi = -s0_lo;
    for (const Image& image : truth) {
        const auto &s0 = image.channel("S0"), &s1 = image.channel("S1"), &s2 = image.channel("S2");
        for (std::size_t i = 0; i < s0.size(); ++i) {
            if (!std::isfinite(s0[i]) || !std::isfinite(s1[i]) || !std::isfinite(s2[i])) continue;
            const double polarized = 0.5 * (tau - tau_min) * std::hypot(s1[i], s2[i]);
            const double mean = 0.5 * (tau + tau_min) * s0[i] + background;
            s0_lo = std::min(s0_lo, static_cast<double>(s0[i]));
            s0_hi = std::max(s0_hi, static_cast<double>(s0[i]));
            det_lo = std::min(det_lo, mean - polarized);
            det_hi = std::max(det_hi, mean + polarized);
        }
    }
    if (!std::isfinite(s0_lo))
        fail("twin: the truth renders have no finite Stokes pixel to derive blackbody set-points");
    out.scene_s0_min = s0_lo;
    out.scene_s0_max = s0_hi;
    std::vector<std::string> limits;
    const auto setpoint = [&](double radiance, double margin_k, const char* what) {
        const double k = band.brightness_temperature(std::max(radiance, 1e-9)) + margin_k;
        const Clamped c = clamp_to_laboratory(k);
        if (c.clamped)
            limits.push_back(fmt::format(
                "the {} set-point would be {:.1f} K, beyond the laboratory's blackbodies "
                "({:.2f}–{:.2f} K): clamped, so part of the range is extrapolated",
                what, k, kColdestBlackbodyK, kWarmestBlackbodyK));
        return c.k;
    };
    // Through the polarizer the blackbody's own detector radiance is ½(τ + τ_min)L_bb + B: the
    // radiometric range must hold those frames as well as the scene's.
    const double pol_lo = setpoint(s0_lo, -kSetpointMarginK, "coldest polarimetric");
    const double pol_hi = setpoint(s0_hi, kSetpointMarginK, "warmest polarimetric");
    out.polarimetric_k = {pol_lo, pol_hi};
    det_lo = std::min(det_lo, 0.5 * (tau + tau_min) * band.radiance(pol_lo) + background);
    det_hi = std::max(det_hi, 0.5 * (tau + tau_min) * band.radiance(pol_hi) + background);
    out.detector_radiance_min = det_lo;
    out.detector_radiance_max = det_hi;
    const double rad_lo = setpoint(det_lo, -kSetpointMarginK, "coldest radiometric");
    const double rad_hi = setpoint(det_hi, kSetpointMarginK, "warmest radiometric");
    out.radiometric_k = {rad_lo, 0.5 * (rad_lo + rad_hi), rad_hi};
    for (const auto& l : limits) out.limitation += (out.limitation.empty() ? "" : "; ") + l;
    return out;
}

}  // namespace tirpol::twin
