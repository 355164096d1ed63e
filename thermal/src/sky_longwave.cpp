#include "tirpol/thermal/sky_longwave.h"

#include <algorithm>
#include <cmath>

#include "tirpol/core/error.h"
#include "tirpol/core/geometry.h"

namespace tirpol::thermal {

namespace {
constexpr double kMagnusA = 17.625;
constexpr double kMagnusB_C = 243.04;
}  // namespace

double saturation_vapour_pressure_hpa(double t_c) {
    return 6.1094 * std::exp(kMagnusA * t_c / (t_c + kMagnusB_C));
}

double dew_point_c(double t_c, double rh_pct) {
    if (!(rh_pct > 0.0 && rh_pct <= 100.0)) fail("relative humidity {} % outside (0, 100]", rh_pct);
    const double g = std::log(rh_pct / 100.0) + kMagnusA * t_c / (kMagnusB_C + t_c);
    return kMagnusB_C * g / (kMagnusA - g);
}

double relative_humidity_pct(double t_c, double dew_c) {
    return 100.0 * saturation_vapour_pressure_hpa(dew_c) / saturation_vapour_pressure_hpa(t_c);
}

ClearSkyModel parse_clear_sky_model(const std::string& name) {
    if (name == "berdahl-martin") return ClearSkyModel::BerdahlMartin1984;
    if (name == "brutsaert") return ClearSkyModel::Brutsaert1975;
    if (name == "clark-allen") return ClearSkyModel::ClarkAllen1978;
    if (name == "idso") return ClearSkyModel::Idso1981;
    fail("unknown clear-sky model '{}'; expected berdahl-martin, brutsaert, clark-allen or idso",
         name);
}

const char* to_string(ClearSkyModel model) {
    switch (model) {
        case ClearSkyModel::BerdahlMartin1984:
            return "berdahl-martin";
        case ClearSkyModel::Brutsaert1975:
            return "brutsaert";
        case ClearSkyModel::ClarkAllen1978:
            return "clark-allen";
        case ClearSkyModel::Idso1981:
            return "idso";
    }
    return "?";
}

double clear_sky_emissivity(ClearSkyModel model, const SkyConditions& c) {
    const double ta_k = c.air_temperature_c + kZeroCelsiusK;
    const double e_hpa = saturation_vapour_pressure_hpa(c.dew_point_c);
    switch (model) {
        case ClearSkyModel::BerdahlMartin1984: {
            const double t = c.dew_point_c / 100.0;
            return 0.711 + 0.56 * t + 0.73 * t * t +
                   0.013 * std::cos(2.0 * kPi * c.local_solar_hour / 24.0) +
                   0.00012 * (c.pressure_hpa - 1000.0);
        }
        case ClearSkyModel::Brutsaert1975:
            return 1.24 * std::pow(e_hpa / ta_k, 1.0 / 7.0);
        case ClearSkyModel::ClarkAllen1978:
            return 0.787 + 0.764 * std::log((c.dew_point_c + kZeroCelsiusK) / 273.0);
        case ClearSkyModel::Idso1981:
            return 0.70 + 5.95e-5 * e_hpa * std::exp(1500.0 / ta_k);
    }
    return 0.0;
}

double clark_allen_cloud_factor(double n) {
    return 1.0 + 0.0224 * n - 0.0035 * n * n + 0.00028 * n * n * n;
}

double sky_emissivity(ClearSkyModel model, const SkyConditions& c) {
    return std::min(
        1.0, clear_sky_emissivity(model, c) * clark_allen_cloud_factor(c.opaque_sky_cover_tenths));
}

double window_sky_emissivity(const SkyConditions& c) {
    const double ta_k = c.air_temperature_c + kZeroCelsiusK;
    const double e_hpa = saturation_vapour_pressure_hpa(c.dew_point_c);
    const double clear = std::min(1.0, 0.24 + 2.98e-8 * e_hpa * e_hpa * std::exp(3000.0 / ta_k));
    const double n = std::clamp(c.opaque_sky_cover_tenths / 10.0, 0.0, 1.0);
    return clear + (1.0 - clear) * n;
}

double directional_sky_emissivity_cos(double zenith_emissivity, double cos_zenith) {
    if (cos_zenith <= 1e-6) return 1.0;
    return 1.0 - std::pow(1.0 - std::clamp(zenith_emissivity, 0.0, 1.0), 1.0 / cos_zenith);
}

double directional_sky_emissivity(double zenith_emissivity, double zenith_deg) {
    return directional_sky_emissivity_cos(zenith_emissivity, std::cos(deg_to_rad(zenith_deg)));
}

double hemispherical_from_zenith_emissivity(double zenith_emissivity) {
    // 2∫₀¹ (1 − e^(−τ/μ)) μ dμ = 1 − 2E₃(τ), τ = −ln(1 − ε_zenith) the layer's vertical optical
    // depth; E₃(x) = [e^(−x)(1 − x) + x² E₁(x)] / 2 (Abramowitz & Stegun 5.1.14) and E₁(x) =
    // −Ei(−x).
    const double ez = std::clamp(zenith_emissivity, 0.0, 1.0);
    if (ez <= 0.0) return 0.0;
    if (ez >= 1.0) return 1.0;
    const double tau = -std::log1p(-ez);
    const double e1 = -std::expint(-tau);
    const double e3 = 0.5 * (std::exp(-tau) * (1.0 - tau) + tau * tau * e1);
    return 1.0 - 2.0 * e3;
}

double zenith_from_hemispherical_emissivity(double hemispherical) {
    if (!(hemispherical >= 0.0 && hemispherical <= 1.0))
        fail("sky emissivity {} outside [0, 1]", hemispherical);
    double lo = 0.0, hi = 1.0;
    while (hi - lo > 1e-12) {
        const double mid = 0.5 * (lo + hi);
        (hemispherical_from_zenith_emissivity(mid) < hemispherical ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

SkyRadianceModel::SkyRadianceModel(double air_temperature_k, double broadband, double window)
    : m_air_temperature_k(air_temperature_k),
      m_broadband_hemispherical(broadband),
      m_window_hemispherical(window),
      m_broadband_zenith(zenith_from_hemispherical_emissivity(std::clamp(broadband, 0.0, 1.0))),
      m_window_zenith(zenith_from_hemispherical_emissivity(std::clamp(window, 0.0, 1.0))) {
    if (!(air_temperature_k > 0.0))
        fail("sky: air temperature {} K must be positive", air_temperature_k);
}

double SkyRadianceModel::horizontal_irradiance_w_m2() const {
    const double t2 = m_air_temperature_k * m_air_temperature_k;
    return m_broadband_hemispherical * kStefanBoltzmann * t2 * t2;
}

double SkyRadianceModel::broadband_radiance(double zenith_deg) const {
    const double t2 = m_air_temperature_k * m_air_temperature_k;
    // Scaled so the cosine-weighted integral reproduces the hemispherical value exactly even where
    // the zenith emissivity was clamped (ε_h > 1 from a measured IR irradiance above σT_a⁴).
    const double scale = m_broadband_hemispherical /
                         std::max(1e-12, hemispherical_from_zenith_emissivity(m_broadband_zenith));
    return scale * directional_sky_emissivity(m_broadband_zenith, zenith_deg) * kStefanBoltzmann *
           t2 * t2 / kPi;
}

double SkyRadianceModel::band_radiance(const Band& band, double zenith_deg) const {
    return directional_sky_emissivity(m_window_zenith, zenith_deg) *
           band.radiance(m_air_temperature_k);
}

double SkyRadianceModel::facet_irradiance_w_m2(double tilt_deg, double ground_temperature_k) const {
    const double f_sky = 0.5 * (1.0 + std::cos(deg_to_rad(tilt_deg)));
    const double g2 = ground_temperature_k * ground_temperature_k;
    return f_sky * horizontal_irradiance_w_m2() + (1.0 - f_sky) * kStefanBoltzmann * g2 * g2;
}

}  // namespace tirpol::thermal
