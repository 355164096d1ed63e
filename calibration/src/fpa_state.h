#pragma once
// Gain and offset of a radiometric calibration at one camera (FPA) temperature, evaluated per pixel
// inside the hot loops. Validated once in the constructor, so the loops never throw (STYLE.md).

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/calibration/radiometric.h"
#include "tirpol/core/error.h"

namespace tirpol::calibration::detail {

class FpaState {
public:
    /// `what` names the frame in the error thrown when `cal` depends on the FPA temperature and
    /// `fpa_temperature_k` is missing or not a temperature.
    FpaState(const RadiometricCalibration& cal, std::optional<double> fpa_temperature_k,
             const std::string& what)
        : m_cal(cal) {
        const int degree = cal.fpa_degree();
        if (degree == 0) return;
        if (!fpa_temperature_k)
            fail(
                "{}: the calibration depends on the camera's FPA temperature (fitted over "
                "{:.2f}–{:.2f} K) but no "
                "FPA temperature is known for this frame; expected the record's fpa_temperature_k",
                what, cal.fpa_min_k, cal.fpa_max_k);
        if (!(*fpa_temperature_k > 0.0) || !std::isfinite(*fpa_temperature_k))
            fail("{}: FPA temperature {} K; expected a finite temperature above 0 K", what,
                 *fpa_temperature_k);
        const double dt = *fpa_temperature_k - cal.fpa_reference_k;
        double p = 1.0;
        for (int a = 0; a < degree; ++a) m_dt_power.push_back(p *= dt);
    }

    double offset(std::size_t i) const {
        double o = m_cal.offset[i];
        for (std::size_t a = 0; a < m_dt_power.size(); ++a)
            o += m_cal.offset_fpa[a][i] * m_dt_power[a];
        return o;
    }
    double gain(std::size_t i) const {
        double g = m_cal.gain[i];
        for (std::size_t a = 0; a < m_dt_power.size(); ++a)
            g += m_cal.gain_fpa[a][i] * m_dt_power[a];
        return g;
    }
    double quadratic(std::size_t i) const {
        return m_cal.quadratic.empty() ? 0.0 : m_cal.quadratic[i];
    }

private:
    const RadiometricCalibration& m_cal;
    std::vector<double> m_dt_power;  // ΔT^1 … ΔT^degree
};

}  // namespace tirpol::calibration::detail
