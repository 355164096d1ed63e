#include <algorithm>
#include <cmath>

#include "sky_model.h"
#include "temperature_value.h"
#include "tirpol/core/error.h"
#include "tirpol/simulation/scene.h"

namespace tirpol::simulation {

Sky::Sky() : Sky(uniform(0.0)) {}

Sky::Sky(std::shared_ptr<const SkyModel> model) : m_model(std::move(model)) {
    if (!m_model) fail("Sky: no sky model");
}

double Sky::emissivity(double cos_zenith) const { return m_model->emissivity(cos_zenith); }

double Sky::temperature_k(double cos_zenith) const { return m_model->temperature_k(cos_zenith); }

double Sky::spectral_radiance(double wavelength_um, const Vec3& direction) const {
    const double c = direction.z();
    return emissivity(c) * planck_radiance(wavelength_um, temperature_k(c));
}

Sky::AtWavelength Sky::at_wavelength(double wavelength_um) const {
    AtWavelength sky;
    sky.m_model = m_model.get();
    sky.m_wavelength_um = wavelength_um;
    if (const auto t = m_model->uniform_temperature_k()) {
        sky.m_isothermal = true;
        sky.m_blackbody = planck_radiance(wavelength_um, *t);
    }
    return sky;
}

double Sky::AtWavelength::spectral_radiance(const Vec3& direction) const {
    const double c = direction.z();
    const double emissivity = m_model->emissivity_per_path(c);
    if (m_isothermal) return emissivity * m_blackbody;
    return emissivity * planck_radiance(m_wavelength_um, m_model->temperature_k(c));
}

Sun Sun::from_config(const ConfigNode& node, const Band& band) {
    node.check_keys({"elevation_deg", "azimuth_deg", "direction", "temperature", "radiance",
                     "solid_angle_sr", "transmittance"});
    Sun sun;
    if (node.has("direction") == node.has("elevation_deg"))
        node.fail("sun: give exactly one of direction [x, y, z] or elevation_deg + azimuth_deg");
    if (node.has("direction")) {
        const ConfigNode d = node.at("direction");
        const auto v = d.as<std::vector<double>>();
        if (v.size() != 3 || Vec3(v[0], v[1], v[2]).norm() == 0.0)
            d.fail("expected a non-zero vector [x, y, z] toward the sun");
        sun.direction = Vec3(v[0], v[1], v[2]).normalized();
    } else {
        const double el = deg_to_rad(node.get_in_range("elevation_deg", -90.0, 90.0));
        const double az = deg_to_rad(node.get_in_range("azimuth_deg", -360.0, 360.0));
        sun.direction =
            Vec3(std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el));
    }
    sun.solid_angle_sr = node.has("solid_angle_sr") ? node.get_in_range("solid_angle_sr", 1e-9, 0.1)
                                                    : sun.solid_angle_sr;
    if (node.has("temperature") && node.has("radiance"))
        node.fail("sun: give temperature (+ transmittance) or a band radiance, not both");
    if (node.has("temperature"))
        sun.temperature_k = temperature_k_from_config(node.at("temperature"));
    sun.transmittance =
        node.has("transmittance") ? node.get_in_range("transmittance", 0.0, 1.0) : 1.0;
    if (node.has("radiance")) {
        if (node.has("transmittance"))
            node.at("transmittance").fail("transmittance only goes with temperature");
        sun.temperature_k = band.brightness_temperature(node.get_in_range("radiance", 1e-12, 1e12));
    }
    return sun;
}

double Sun::spectral_radiance(double wavelength_um) const {
    return transmittance * planck_radiance(wavelength_um, temperature_k);
}

}  // namespace tirpol::simulation
