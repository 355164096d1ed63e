#pragma once
/// \file microfacet.h
/// The paper's generalized micro-facet pBRDF ("Shell target" family): polarized Fresnel reflection
/// on Gaussian-distributed facets with shadowing, plus unpolarized diffuse and volume terms. The
/// formulas and their sources are in shell_target_math.h; this class supplies spectral parameters,
/// evaluation, and importance sampling.

#include <optional>

#include "tirpol/materials/complex_index.h"
#include "tirpol/materials/pbrdf.h"
#include "tirpol/materials/shell_target_math.h"
#include "tirpol/materials/spectral_value.h"

namespace tirpol::materials {

/// Spectral parameters of the micro-facet model (names as in DIRSIG's Shell-target files).
struct MicrofacetParameters {
    RefractiveIndexTable index = RefractiveIndexTable::constant({1.5, 0.0});
    SpectralValue sigma = 0.1;     ///< slope standard deviation per axis, > 0
    SpectralValue bias = 1.0;      ///< specular scale, ≥ 0
    SpectralValue tau_deg = 90.0;  ///< Beard–Maxwell τ, degrees, > 0
    SpectralValue omega_deg =
        1e6;  ///< Beard–Maxwell Ω, degrees, > 0 (huge: no Beard–Maxwell shadowing)
    SpectralValue rho_d = 0.0;  ///< diffuse BRDF, 1/sr
    SpectralValue rho_v = 0.0;  ///< volume coefficient, 1/sr
};

/// A facet normal of the Gaussian slope distribution with standard deviation `sigma` per axis,
/// drawn from the normals visible from `wo` (surface-local, z > 0): density G1(wo)·D(h)·max(0,
/// h·wo)/cosθo, G1 = 1/(1 + Λ(wo)) (shell_target_math.h), from two uniforms in [0, 1) (Heitz &
/// d'Eon, EGSR 2014). Reflected about h, wo gives specular weights f·cosθi/pdf =
/// bias·F·SO·G/G1(wo), bounded.
Vec3 sample_visible_normal(const Vec3& wo, double sigma, double u1, double u2);

class MicrofacetBrdf final : public PolarizedBrdf {
public:
    explicit MicrofacetBrdf(MicrofacetParameters parameters);

    std::string model() const override { return "microfacet"; }
    MuellerMatrix eval(const Vec3& wi, const Vec3& wo, double wavelength_um) const override;
    /// With probability p_spec (specular_sampling_probability): a facet normal h drawn from the
    /// normals visible from wo, G1(wo)·D(h)·(h·wo)/cosθo (sample_visible_normal), wi = reflection
    /// of wo about h; otherwise a cosine-weighted direction. pdf is the mixture of both densities,
    /// so the weight f·cosθi/pdf is the one-sample multiple-importance estimator (Veach 1997,
    /// §9.2.4). Reflections below the horizon return pdf = 0.
    BrdfSample sample(const Vec3& wo, double wavelength_um, double u1, double u2) const override;
    /// The same mixture with the facet normal drawn from D(h)·cosθh (tan²θh = −2σ² ln(1 − u), φ =
    /// 2πu2): unbounded weights near grazing views, but a smoother map of u than the visible
    /// normals' (whose inverse CDFs steepen at the ends of [0, 1]), so the emissivity quadrature
    /// stays at its accuracy
    /// (|Δε| < 2e-4 at 89°, σ = 0.3; the visible-normal map gave 2e-3).
    BrdfSample quadrature_sample(const Vec3& wo, double wavelength_um, double u1,
                                 double u2) const override;
    double pdf(const Vec3& wi, const Vec3& wo, double wavelength_um) const override;
    bool is_isotropic() const override { return true; }
    std::vector<BrdfParameter> parameters(double wavelength_um) const override;
    std::vector<double> sample_u1_breaks(const Vec3& wo, double wavelength_um) const override;
    std::pair<double, double> valid_wavelength_range_um() const override;

    /// Parameters at one wavelength in the templated form (radians for τ, Ω).
    ShellTargetParameters<double> at(double wavelength_um) const;
    const MicrofacetParameters& spectral_parameters() const { return m_parameters; }

    /// Probability with which `sample` draws from the specular lobe for exitant `wo`: the share of
    /// the Fresnel reflectance at wo's angle (× bias) in an estimate of the total albedo, clamped
    /// to [0.05, 0.95]; 1 without diffuse/volume terms.
    double specular_sampling_probability(const Vec3& wo, double wavelength_um) const;

private:
    /// The parameters at one wavelength, interpolated from the spectral tables.
    ShellTargetParameters<double> interpolated_parameters(double wavelength_um) const;

    MicrofacetParameters m_parameters;
    /// Set when no parameter depends on wavelength: `at` returns it without looking anything up.
    std::optional<ShellTargetParameters<double>> m_constant_parameters;
};

}  // namespace tirpol::materials
