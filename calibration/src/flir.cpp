#include <cmath>
#include <limits>

#include "tirpol/calibration/flir_image.h"
#include "tirpol/core/error.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::calibration {

double flir_blackbody_raw(const FlirPlanck& p, double temperature_k) {
    return p.r1 / (p.r2 * (std::exp(p.b / temperature_k) - p.f)) - p.o;
}

double flir_blackbody_temperature(const FlirPlanck& p, double raw) {
    const double arg = p.r1 / (p.r2 * (raw + p.o)) + p.f;
    if (!(raw + p.o > 0.0) || !(arg > 1.0)) return std::numeric_limits<double>::quiet_NaN();
    return p.b / std::log(arg);
}

double flir_atmospheric_transmission(double distance_m, double air_k, double humidity_pct,
                                     const FlirAtmosphereConstants& c) {
    const double t = air_k - kZeroCelsiusK;
    const double h2o =
        humidity_pct / 100.0 *
        std::exp(1.5587 + 0.06939 * t - 0.00027816 * t * t + 0.00000068455 * t * t * t);
    const double sd = std::sqrt(distance_m), sh = std::sqrt(h2o);
    return c.x * std::exp(-sd * (c.alpha1 + c.beta1 * sh)) +
           (1.0 - c.x) * std::exp(-sd * (c.alpha2 + c.beta2 * sh));
}

namespace {
// raw = gain·raw_bb(T_obj) + rest: the measurement model is affine in the object's blackbody raw.
struct Affine {
    double gain, rest;
};
Affine measurement(const FlirPlanck& p, const FlirConditions& c) {
    const double tau = flir_atmospheric_transmission(c.distance_m / 2.0, c.atmosphere_k,
                                                     c.humidity_pct, c.atmosphere);
    const double tw = c.window_transmission;
    const double path = tau * tw * tau;
    const double rest = (1.0 - c.emissivity) * path * flir_blackbody_raw(p, c.reflected_k) +
                        (1.0 - tau) * tw * tau * flir_blackbody_raw(p, c.atmosphere_k) +
                        (1.0 - tw) * tau * flir_blackbody_raw(p, c.window_k) +
                        (1.0 - tau) * flir_blackbody_raw(p, c.atmosphere_k);
    return {c.emissivity * path, rest};
}
}  // namespace

double flir_raw_from_temperature(const FlirPlanck& p, double object_k, const FlirConditions& c) {
    const Affine a = measurement(p, c);
    return a.gain * flir_blackbody_raw(p, object_k) + a.rest;
}

double flir_temperature_from_raw(const FlirPlanck& p, double raw, const FlirConditions& c) {
    const Affine a = measurement(p, c);
    return flir_blackbody_temperature(p, (raw - a.rest) / a.gain);
}

void validate_flir(const FlirPlanck& p, const FlirConditions& c) {
    if (!(p.r1 > 0.0) || !(p.r2 > 0.0) || !(p.b > 0.0) || !std::isfinite(p.r1 * p.r2 * p.b))
        fail("FLIR Planck constants R1={}, R2={}, B={}: expected all finite and > 0", p.r1, p.r2,
             p.b);
    if (!std::isfinite(p.f) || !std::isfinite(p.o))
        fail("FLIR Planck constants F={}, O={}: expected finite numbers", p.f, p.o);
    // The object signal is (signal − (1 − ε)·reflected − …) / ε: below
    // limits::kMinCorrectionEmissivity one count of noise becomes ≥ 100 counts, and ε = 1e-300
    // overflows to an all-NaN image.
    if (!(c.emissivity >= limits::kMinCorrectionEmissivity && c.emissivity <= 1.0))
        fail(
            "emissivity {}: expected a value in [{}, 1] (below {}, the reflected term dominates "
            "and 1/ε amplifies "
            "noise beyond use)",
            c.emissivity, limits::kMinCorrectionEmissivity, limits::kMinCorrectionEmissivity);
    if (!(c.window_transmission >= limits::kMinCorrectionEmissivity &&
          c.window_transmission <= 1.0))
        fail("window transmission {}: expected a value in [{}, 1]", c.window_transmission,
             limits::kMinCorrectionEmissivity);
    if (!(c.distance_m >= 0.0 && std::isfinite(c.distance_m)))
        fail("distance {} m: expected finite and ≥ 0", c.distance_m);
    if (!(c.humidity_pct >= 0.0 && c.humidity_pct <= 100.0))
        fail("relative humidity {} %: expected 0–100", c.humidity_pct);
    for (double t : {c.reflected_k, c.atmosphere_k, c.window_k})
        if (!(t >= limits::kMinTemperatureK && t <= limits::kMaxTemperatureK))
            fail("temperature {} K: expected {} to {} K", t, limits::kMinTemperatureK,
                 limits::kMaxTemperatureK);
}

}  // namespace tirpol::calibration
