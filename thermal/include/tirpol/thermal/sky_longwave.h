#pragma once
/// \file sky_longwave.h
/// Longwave (thermal) radiation of the sky from screen-level weather: clear-sky emissivity models,
/// the cloud correction, the angular dependence of sky radiance and the 8–14 µm window. The sky is
/// treated as a grey emitter at the screen-level air temperature T_a with an effective emissivity,
/// so the downwelling irradiance on a horizontal surface is E = ε σ T_a⁴ and the radiance from
/// zenith angle θ is L(θ) = ε(θ) σ T_a⁴ / π (broadband) or ε_w(θ) L_band(T_a) (window band).

#include "tirpol/core/radiometry.h"

namespace tirpol::thermal {

/// Saturation vapour pressure over water, hPa, Magnus form with Alduchov & Eskridge (1996, J. Appl.
/// Meteor. 35, 601) coefficients: 6.1094 exp(17.625 T / (T + 243.04)), T in °C.
double saturation_vapour_pressure_hpa(double temperature_c);
/// Dew point (°C) from air temperature (°C) and relative humidity (%), inverse of the Magnus form.
double dew_point_c(double temperature_c, double relative_humidity_pct);
/// Relative humidity (%) from air temperature and dew point (°C).
double relative_humidity_pct(double temperature_c, double dew_point_c);

enum class ClearSkyModel {
    BerdahlMartin1984,  ///< ε = 0.711 + 0.56 t + 0.73 t², t = T_dp/100 (°C), + 0.013 cos(2π h/24) +
                        ///< 0.00012 (P − 1000)
    Brutsaert1975,   ///< ε = 1.24 (e/T_a)^(1/7), e in hPa, T_a in K
    ClarkAllen1978,  ///< ε = 0.787 + 0.764 ln(T_dp/273), T_dp in K
    Idso1981,        ///< ε = 0.70 + 5.95e-5 e exp(1500/T_a), e in hPa, T_a in K
};

/// "berdahl-martin", "brutsaert", "clark-allen", "idso"; throws tirpol::Error naming the allowed
/// names.
ClearSkyModel parse_clear_sky_model(const std::string& name);
const char* to_string(ClearSkyModel model);

/// Screen-level conditions the emissivity models need.
struct SkyConditions {
    double air_temperature_c = 15.0;
    double dew_point_c = 5.0;
    double pressure_hpa = 1013.25;
    double local_solar_hour = 0.0;  ///< hours from local midnight (Berdahl–Martin diurnal term)
    double opaque_sky_cover_tenths = 0.0;  ///< 0 (clear) … 10 (overcast)
};

/// Broadband hemispherical clear-sky emissivity of `model`.
/// Sources: Berdahl & Martin, Solar Energy 32 (1984) 663–664; Brutsaert, Water Resour. Res. 11
/// (1975) 742–744; Clark & Allen, Proc. 2nd Nat. Passive Solar Conf. (1978) 675–678; Idso, Water
/// Resour. Res. 17 (1981) 295–304.
double clear_sky_emissivity(ClearSkyModel model, const SkyConditions& c);

/// Cloud multiplier of Clark & Allen (1978) as used by TARP/EnergyPlus (Walton 1983):
/// 1 + 0.0224 N − 0.0035 N² + 0.00028 N³, N = opaque sky cover in tenths.
double clark_allen_cloud_factor(double opaque_sky_cover_tenths);

/// All-sky broadband emissivity: clear-sky value times the Clark–Allen cloud factor, capped at 1.
double sky_emissivity(ClearSkyModel model, const SkyConditions& c);

/// 8–14 µm window clear-sky hemispherical emissivity, Idso (1981): 0.24 + 2.98e-8 e² exp(3000/T_a),
/// e in hPa, T_a in K; clouds (opaque cover N tenths) are treated as black in the window at T_a:
/// ε = ε_clear + (1 − ε_clear) N/10.
double window_sky_emissivity(const SkyConditions& c);

/// Directional emissivity of a plane-parallel isothermal absorbing atmosphere, Granqvist &
/// Hjortsberg (J. Appl. Phys. 52 (1981) 4205): ε(θ) = 1 − (1 − ε_zenith)^(1/cos θ); 1 at and below
/// the horizon (cos θ ≤ 1e-6: an optically thick path). The one implementation of the law, used by
/// the renderer's sky.
double directional_sky_emissivity_cos(double zenith_emissivity, double cos_zenith);
/// The same law with the zenith angle in degrees.
double directional_sky_emissivity(double zenith_emissivity, double zenith_deg);
/// Hemispherical (cosine-weighted) emissivity 2∫ε(θ) cosθ sinθ dθ of that law; equals 1 − 2E₃(τ)
/// with τ = −ln(1 − ε_zenith).
double hemispherical_from_zenith_emissivity(double zenith_emissivity);
/// Inverse of hemispherical_from_zenith_emissivity (bisection, to 1e-12).
double zenith_from_hemispherical_emissivity(double hemispherical_emissivity);

/// The sky as the renderer and the thermal solver both see it, built from one weather record.
class SkyRadianceModel {
public:
    /// `broadband_hemispherical_emissivity` from a model or from measured horizontal IR (E/σT_a⁴);
    /// `window_hemispherical_emissivity` for 8–14 µm.
    SkyRadianceModel(double air_temperature_k, double broadband_hemispherical_emissivity,
                     double window_hemispherical_emissivity);

    double air_temperature_k() const { return m_air_temperature_k; }
    double broadband_emissivity() const { return m_broadband_hemispherical; }
    double window_emissivity() const { return m_window_hemispherical; }
    /// Zenith values of the angular law that reproduce the hemispherical emissivities.
    double broadband_zenith_emissivity() const { return m_broadband_zenith; }
    double window_zenith_emissivity() const { return m_window_zenith; }

    /// Downwelling broadband irradiance on a horizontal surface, W/m².
    double horizontal_irradiance_w_m2() const;
    /// Broadband radiance from zenith angle θ, W/(m²·sr); its cosine-weighted integral over the
    /// hemisphere equals horizontal_irradiance_w_m2().
    double broadband_radiance(double zenith_deg) const;
    /// Band radiance from zenith angle θ for a band in the 8–14 µm window, W/(m²·sr):
    /// ε_w(θ) L_band(T_a) — the renderer's sky.
    double band_radiance(const Band& band, double zenith_deg) const;
    /// Longwave irradiance (W/m²) on a facet tilted `tilt_deg` from horizontal: the sky seen
    /// through view factor F = (1 + cos tilt)/2 (isotropic approximation, i.e. the sky's
    /// hemispherical value) plus ground at `ground_temperature_k` (black) through 1 − F.
    double facet_irradiance_w_m2(double tilt_deg, double ground_temperature_k) const;

private:
    double m_air_temperature_k;
    double m_broadband_hemispherical;
    double m_window_hemispherical;
    double m_broadband_zenith;
    double m_window_zenith;
};

}  // namespace tirpol::thermal
