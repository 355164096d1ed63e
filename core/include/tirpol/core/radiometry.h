#pragma once
/// \file radiometry.h
/// Planck's law, band integration with a relative spectral response (RSR), and brightness
/// temperature. Wavelengths in micrometres, spectral radiance in W/(m²·sr·µm), band radiance in
/// W/(m²·sr), temperatures in kelvin. Constants: CODATA 2018 (exact SI values since 2019).

#include <filesystem>
#include <optional>
#include <vector>

namespace tirpol {

inline constexpr double kPlanckH = 6.62607015e-34;    ///< J·s (exact)
inline constexpr double kSpeedOfLight = 299792458.0;  ///< m/s (exact)
inline constexpr double kBoltzmannK = 1.380649e-23;   ///< J/K (exact)
/// First radiation constant for radiance, 2hc², in W·µm⁴/(m²·sr).
inline constexpr double kC1L_W_um4_per_m2_sr =
    2.0 * kPlanckH * kSpeedOfLight * kSpeedOfLight * 1e24;
/// Second radiation constant hc/k in µm·K.
inline constexpr double kC2_um_K = kPlanckH * kSpeedOfLight / kBoltzmannK * 1e6;
/// Stefan–Boltzmann constant 2π⁵k⁴/(15h³c²), W/(m²·K⁴) (CODATA 2018 value).
inline constexpr double kStefanBoltzmann = 5.670374419e-8;
/// 0 °C in kelvin (the Celsius scale's definition).
inline constexpr double kZeroCelsiusK = 273.15;

/// Planck spectral radiance of a blackbody, W/(m²·sr·µm). Returns 0 for T ≤ 0.
double planck_radiance(double wavelength_um, double temperature_k);

/// ∂L/∂T of planck_radiance, W/(m²·sr·µm·K).
double planck_radiance_dT(double wavelength_um, double temperature_k);

/// A relative spectral response table (wavelength_um, response ≥ 0), linearly interpolated and zero
/// outside its range.
class SpectralResponse {
public:
    SpectralResponse(std::vector<double> wavelength_um, std::vector<double> response);

    /// Reads a CSV with a header naming `wavelength_um` and `response` columns (any order; other
    /// columns ignored; '#' comment lines allowed). Errors name the file, line and field.
    static SpectralResponse load_csv(const std::filesystem::path& path);

    double operator()(double wavelength_um) const;
    const std::vector<double>& wavelengths_um() const { return m_wavelength_um; }
    const std::vector<double>& responses() const { return m_response; }

private:
    std::vector<double> m_wavelength_um;
    std::vector<double> m_response;
};

/// One quadrature node of a band: ∫ R(λ) f(λ) dλ ≈ Σ weight·f(wavelength).
struct BandNode {
    double wavelength_um;
    double weight_um;  ///< includes the RSR value at the node
};

/// A spectral band [lo, hi] µm with an optional RSR. Integrals use composite Gauss–Legendre
/// quadrature on panels split at the RSR's knots (so a piecewise-linear RSR is integrated exactly)
/// and at most `max_panel_um` wide (Planck is smooth there: relative error < 1e-12).
class Band {
public:
    Band(double lo_um, double hi_um, std::optional<SpectralResponse> rsr = std::nullopt,
         double max_panel_um = 0.25);

    double lo_um() const { return m_lo_um; }
    double hi_um() const { return m_hi_um; }
    const std::optional<SpectralResponse>& rsr() const { return m_rsr; }
    const std::vector<BandNode>& nodes() const { return m_nodes; }

    /// ∫ R(λ) dλ over the band, µm (the band's effective width).
    double effective_width_um() const;

    /// Band radiance ∫ R(λ) L_bb(λ, T) dλ, W/(m²·sr).
    double radiance(double temperature_k) const;

    /// d(band radiance)/dT, W/(m²·sr·K).
    double radiance_dT(double temperature_k) const;

    /// Brightness temperature: the T whose band radiance equals `radiance_w_m2_sr`, to better than
    /// 1e-6 K (Newton's method, bracketed). NaN for a non-positive or non-finite radiance.
    double brightness_temperature(double radiance_w_m2_sr) const;

private:
    double m_lo_um, m_hi_um;
    std::optional<SpectralResponse> m_rsr;
    std::vector<BandNode> m_nodes;
};

}  // namespace tirpol
