#pragma once
/// \file calibration_setpoints.h
/// Blackbody set-points that bracket what the twin's camera will see. The radiometric calibration
/// (polarizer out of the beam) maps counts to the radiance at the detector, so its set-points must
/// span the detector radiance of the scene seen *through* the polarizer, ½(τ + τ_min)S0 ± ½(τ −
/// τ_min)√(S1² + S2²) plus the grid's reflected and emitted background (Chipman, Lam & Young 2018
/// eq 6.35, as the sensor model); the polarimetric calibration (blackbody through the polarizer)
/// must span the scene's S0. A calibration that does not span them extrapolates, and the report
/// says so.

#include <string>
#include <vector>

#include "tirpol/core/image.h"
#include "tirpol/core/radiometry.h"
#include "tirpol/simulation/sensor_model.h"

namespace tirpol::twin {

/// The coldest and warmest blackbody the twin's laboratory may use: an extended-area source cooled
/// to −100 °C (a cryogenically cooled plate; thermo-electric ones reach about −40 °C) and +100 °C.
inline constexpr double kColdestBlackbodyK = 173.15;
inline constexpr double kWarmestBlackbodyK = 373.15;
/// Margin on each side of the expected range, in brightness temperature.
inline constexpr double kSetpointMarginK = 2.0;

struct BlackbodySetpoints {
    std::vector<double>
        radiometric_k;  ///< three, polarizer out: span the detector radiance through the polarizer
    std::vector<double> polarimetric_k;  ///< two, through the polarizer: span the scene's S0
    double detector_radiance_min = 0.0, detector_radiance_max = 0.0;  ///< expected, W/(m²·sr)
    double scene_s0_min = 0.0, scene_s0_max = 0.0;  ///< of the truth renders, W/(m²·sr)
    /// Empty when both ranges are covered with margin; otherwise why not (a set-point was clamped
    /// to the laboratory's blackbody range).
    std::string limitation;
};

/// Set-points from the truth renders' S0, S1, S2 (finite pixels of every view) through `sensor`'s
/// analyzer and grid background, in `band`, with kSetpointMarginK on each side, clamped to
/// [kColdestBlackbodyK, kWarmestBlackbodyK]. Throws tirpol::Error when no render has a finite
/// pixel.
BlackbodySetpoints blackbody_setpoints(const std::vector<Image>& truth,
                                       const simulation::SensorModel& sensor, const Band& band);

}  // namespace tirpol::twin
