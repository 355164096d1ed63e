// `type: clear_sky`: effective emissivity ε(θ) = 1 − (1 − ε_zenith)^(1/cos θ) at the air
// temperature, the plane-parallel absorbing-atmosphere law of Granqvist & Hjortsberg (J. Appl.
// Phys. 52 (1981) 4205), implemented once in thermal::directional_sky_emissivity_cos; ε_zenith
// comes from the scene or from a clear-sky model of the thermal module (Berdahl & Martin 1984 and
// others).

#include <cmath>

#include "sky_model.h"
#include "temperature_value.h"
#include "tirpol/core/error.h"
#include "tirpol/thermal/sky_longwave.h"

namespace tirpol::simulation {

namespace {

class ClearSky final : public SkyModel {
public:
    ClearSky(double air_temperature_k, double zenith_emissivity)
        : m_air_temperature_k(air_temperature_k),
          m_zenith_emissivity(zenith_emissivity),
          m_log_zenith_transmittance(std::log1p(-zenith_emissivity)) {}

    double emissivity(double cos_zenith) const override {
        return thermal::directional_sky_emissivity_cos(m_zenith_emissivity, cos_zenith);
    }
    double temperature_k(double) const override { return m_air_temperature_k; }
    std::optional<double> uniform_temperature_k() const override { return m_air_temperature_k; }
    /// thermal::directional_sky_emissivity_cos with the layer's optical depth hoisted: an exp
    /// instead of a pow per path end.
    double emissivity_per_path(double cos_zenith) const override {
        if (cos_zenith <= 1e-6) return 1.0;
        return -std::expm1(m_log_zenith_transmittance / cos_zenith);
    }

private:
    double m_air_temperature_k;
    double m_zenith_emissivity;
    double m_log_zenith_transmittance;  ///< ln(1 − ε_zenith)
};

}  // namespace

Sky Sky::clear_sky(double air_temperature_k, double zenith_emissivity) {
    if (!(zenith_emissivity > 0.0 && zenith_emissivity <= 1.0))
        fail("clear sky: zenith emissivity must lie in (0, 1], got {}", zenith_emissivity);
    return Sky(std::make_shared<const ClearSky>(air_temperature_k, zenith_emissivity));
}

namespace skies {

Sky clear_sky_from_config(const ConfigNode& node, const Band&) {
    node.check_keys({"type", "air_temperature", "zenith_emissivity"});
    return Sky::clear_sky(temperature_k_from_config(node.at("air_temperature")),
                          node.get_in_range("zenith_emissivity", 1e-6, 1.0));
}

}  // namespace skies

}  // namespace tirpol::simulation
