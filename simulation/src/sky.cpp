#include "tirpol/simulation/sky.h"

#include <algorithm>
#include <cmath>

#include "csv_columns.h"
#include "temperature_value.h"
#include "tirpol/core/error.h"
#include "tirpol/thermal/sky_longwave.h"

namespace tirpol::simulation {

Sky Sky::uniform(double temperature_k) {
    Sky s;
    s.m_kind = Kind::Uniform;
    s.m_temperature_k = temperature_k;
    return s;
}

Sky Sky::clear_sky(double air_temperature_k, double zenith_emissivity) {
    if (!(zenith_emissivity > 0.0 && zenith_emissivity <= 1.0))
        fail("clear sky: zenith emissivity must lie in (0, 1], got {}", zenith_emissivity);
    Sky s;
    s.m_kind = Kind::ClearSky;
    s.m_temperature_k = air_temperature_k;
    s.m_zenith_emissivity = zenith_emissivity;
    return s;
}

Sky Sky::table(std::vector<double> zenith_deg, std::vector<double> band_radiance,
               const Band& band) {
    if (zenith_deg.size() != band_radiance.size() || zenith_deg.empty())
        fail("sky table: need matching, non-empty zenith and radiance columns");
    Sky s;
    s.m_kind = Kind::Table;
    for (std::size_t i = 0; i < zenith_deg.size(); ++i) {
        if (i > 0 && !(zenith_deg[i] > zenith_deg[i - 1]))
            fail("sky table: zenith_deg must increase strictly (row {}: {} after {})", i + 1,
                 zenith_deg[i], zenith_deg[i - 1]);
        if (!(band_radiance[i] > 0.0))
            fail("sky table: radiance must be positive (row {}: {})", i + 1, band_radiance[i]);
        s.m_brightness_k.push_back(band.brightness_temperature(band_radiance[i]));
    }
    s.m_zenith_deg = std::move(zenith_deg);
    return s;
}

Sky Sky::from_config(const ConfigNode& node, const Band& band) {
    const std::string type = node.get<std::string>("type");
    if (type == "uniform") {
        node.check_keys({"type", "temperature", "radiance"});
        if (node.has("temperature") == node.has("radiance"))
            node.fail(
                "uniform sky: give exactly one of temperature (K or \"°C\") or radiance (band, "
                "W/(m²·sr))");
        if (node.has("temperature"))
            return uniform(temperature_k_from_config(node.at("temperature")));
        const double l = node.get_in_range("radiance", 1e-12, 1e9);
        return uniform(band.brightness_temperature(l));
    }
    if (type == "clear_sky") {
        node.check_keys({"type", "air_temperature", "zenith_emissivity"});
        return clear_sky(temperature_k_from_config(node.at("air_temperature")),
                         node.get_in_range("zenith_emissivity", 1e-6, 1.0));
    }
    if (type == "table") {
        node.check_keys({"type", "file"});
        const auto path = node.resolve_path(node.get<std::string>("file"));
        if (!std::filesystem::exists(path))
            node.at("file").fail("sky table file not found: " + path.string());
        auto cols = read_csv_columns(path, {"zenith_deg", "radiance_w_m2_sr"});
        return table(std::move(cols[0]), std::move(cols[1]), band);
    }
    node.at("type").fail("unknown sky type \"" + type +
                         "\" (expected uniform, clear_sky or table)");
}

double Sky::emissivity(double cos_zenith) const {
    if (m_kind != Kind::ClearSky) return 1.0;
    return thermal::directional_sky_emissivity_cos(m_zenith_emissivity, cos_zenith);
}

double Sky::temperature_k(double cos_zenith) const {
    if (m_kind != Kind::Table) return m_temperature_k;
    const double z = rad_to_deg(std::acos(std::clamp(cos_zenith, 0.0, 1.0)));
    if (z <= m_zenith_deg.front()) return m_brightness_k.front();
    if (z >= m_zenith_deg.back()) return m_brightness_k.back();
    const auto it = std::upper_bound(m_zenith_deg.begin(), m_zenith_deg.end(), z);
    const auto i = static_cast<std::size_t>(it - m_zenith_deg.begin());
    const double t = (z - m_zenith_deg[i - 1]) / (m_zenith_deg[i] - m_zenith_deg[i - 1]);
    return (1.0 - t) * m_brightness_k[i - 1] + t * m_brightness_k[i];
}

double Sky::spectral_radiance(double wavelength_um, const Vec3& direction) const {
    const double c = direction.z();
    return emissivity(c) * planck_radiance(wavelength_um, temperature_k(c));
}

Sky::AtWavelength Sky::at_wavelength(double wavelength_um) const {
    AtWavelength sky;
    sky.m_sky = this;
    sky.m_wavelength_um = wavelength_um;
    if (m_kind != Kind::Table) sky.m_blackbody = planck_radiance(wavelength_um, m_temperature_k);
    sky.m_log_zenith_transmittance = std::log1p(-std::clamp(m_zenith_emissivity, 0.0, 1.0));
    return sky;
}

double Sky::AtWavelength::spectral_radiance(const Vec3& direction) const {
    switch (m_sky->m_kind) {
        case Kind::Table:
            return m_sky->spectral_radiance(m_wavelength_um, direction);
        case Kind::ClearSky:
            // thermal::directional_sky_emissivity_cos, with the layer's optical depth hoisted.
            if (direction.z() <= 1e-6) return m_blackbody;
            return -std::expm1(m_log_zenith_transmittance / direction.z()) * m_blackbody;
        case Kind::Uniform:
            break;
    }
    return m_blackbody;
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
