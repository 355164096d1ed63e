// `type: uniform`: ε = 1 at one temperature, given as a temperature (K or "°C") or as the
// brightness temperature of a band radiance.

#include "sky_model.h"
#include "temperature_value.h"

namespace tirpol::simulation {

namespace {

class UniformSky final : public SkyModel {
public:
    explicit UniformSky(double temperature_k) : m_temperature_k(temperature_k) {}
    double emissivity(double) const override { return 1.0; }
    double temperature_k(double) const override { return m_temperature_k; }
    std::optional<double> uniform_temperature_k() const override { return m_temperature_k; }

private:
    double m_temperature_k;
};

}  // namespace

Sky Sky::uniform(double temperature_k) {
    return Sky(std::make_shared<const UniformSky>(temperature_k));
}

namespace skies {

Sky uniform_from_config(const ConfigNode& node, const Band& band) {
    node.check_keys({"type", "temperature", "radiance"});
    if (node.has("temperature") == node.has("radiance"))
        node.fail(
            "uniform sky: give exactly one of temperature (K or \"°C\") or radiance (band, "
            "W/(m²·sr))");
    if (node.has("temperature"))
        return Sky::uniform(temperature_k_from_config(node.at("temperature")));
    const double l = node.get_in_range("radiance", 1e-12, 1e9);
    return Sky::uniform(band.brightness_temperature(l));
}

}  // namespace skies

}  // namespace tirpol::simulation
