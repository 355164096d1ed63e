#pragma once
/// \file microfacet.h
/// The paper's generalized micro-facet pBRDF ("Shell target" family): polarized Fresnel reflection
/// on Gaussian-distributed facets with shadowing, plus unpolarized diffuse and volume terms. The
/// formulas and their sources are in shell_target_math.h; this class supplies spectral parameters,
/// evaluation, and importance sampling.
///
/// A model parameter that is either a constant or a table over wavelength (µm), linearly
/// interpolated. Material files write either `sigma: 0.3` or `sigma: {wavelength_um: [8, 10, 12],
/// value: [...]}`.
///
/// The math of the micro-facet pBRDF of the paper's §2.3.1–2.3.2 ("Shell target" family, Shell 2005
/// thesis as used in DIRSIG), written as templates on the parameter scalar T so that
/// tirpol::fitting can evaluate it with ceres::Jet. Geometry (directions) is plain double: it is
/// data, not fitted.
///
///   f(wi→wo) = bias · D(θN) · G(wi, wo) · SO(θN, β) / (4 cosθi cosθo) · R(αo)·M_F(β)·R(αi)
///            + (ρ_D + 2ρ_V / (cosθi + cosθo)) · diag(1, 0, 0, 0)                       [1/sr]
///
/// h = (wi + wo)/|wi + wo| is the facet normal that reflects wi into wo, θN its tilt from the
/// surface normal, β the angle of incidence on the facet (cos β = h·wi).
///  * D: Gaussian distribution of facet slopes with standard deviation σ in each of x and y
///    (Priest & Germer 2000, "Polarimetric BRDF in the microfacet model", Proc. MSS Passive
///    Sensors; same density as SCATMECH's Gaussian slope distribution with s = √2·σ):
///      D(θN) = exp(−tan²θN / (2σ²)) / (2π σ² cos⁴θN),  normalised so ∫ D cosθN dω = 1.
///  * M_F(β): Fresnel Mueller matrix of the facet with index n + i·k (fresnel.h), in the facet's
///  s/p
///    frames; R(αi), R(αo) rotate from the macro-surface s/p frames (pbrdf.h) to the facet's and
///    back (paper eq 11), which is how Priest & Germer carry polarization off the plane of
///    incidence.
///  * SO: Beard–Maxwell shadowing/obscuration (Maxwell, Beard, Weiner, Ladd & Ladd 1973, ERIM
///  report
///    AFAL-TR-73-303; as in the NEFDS Beard–Maxwell model and SCATMECH's
///    Maxwell_Beard_Shadow_Function):
///      SO = (1 + (θN/Ω)·exp(−2β/τ)) / (1 + θN/Ω),  τ and Ω in radians.
///  * G: Smith's masking–shadowing for the same Gaussian surface, height-correlated form
///    (B. G. Smith, IEEE Trans. Antennas Propag. AP-15, 668 (1967); Heitz, JCGT 3(2), 2014, eq 99):
///      G = 1 / (1 + Λ(θi) + Λ(θo)),  Λ(θ) = ½·(exp(−a²)/(a√π) − erfc(a)),  a = cotθ / (√2 σ).
///    CHOICE (not in Shell's published description, which uses Beard–Maxwell SO alone): without G
///    the specular directional-hemispherical reflectance grows like 1/cosθo and exceeds 1 near
///    grazing — the breakdown the paper blames for its SUV-roof artifacts (§4). Smith's G makes the
///    specular DHR ≤ max Fresnel reflectance at every angle (energy conservation), and G → 1 as σ →
///    0.
///  * bias: dimensionless scale factor on the specular lobe. CHOICE: DIRSIG's documentation of the
///  Shell
///    target's `bias` was not available to us; we treat it like Beard–Maxwell's specular scale B,
///    with bias = 1 the physical Priest–Germer normalisation (bias ≤ 1 keeps energy conservation).
///  * ρ_D: Lambertian diffuse term and ρ_V: Beard–Maxwell volume term 2ρ_V/(cosθi + cosθo), both in
///    1/sr and unpolarized (paper §2.3.1: "this model treats the volume term as completely
///    unpolarized"; NEFDS Beard–Maxwell documentation, Westlund & Meyer, Graphics Interface 2002,
///    eq 1).
/// Every term is reciprocal (symmetric in wi ↔ wo); Mueller reciprocity holds with pbrdf.h's Q.

#include <cmath>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "tirpol/core/geometry.h"
#include "tirpol/materials/fresnel.h"
#include "tirpol/materials/pbrdf.h"

namespace tirpol::materials {

/// Parameters of the Shell-target micro-facet model, with DIRSIG's names.
template <typename T>
struct ShellTargetParameters {
    T n;          ///< real part of the complex index
    T k;          ///< imaginary part (≥ 0: absorbing)
    T sigma;      ///< standard deviation of the facet slope along x and along y (dimensionless)
    T bias;       ///< scale of the specular lobe (1 = Priest–Germer normalisation)
    T tau_rad;    ///< Beard–Maxwell τ (radians)
    T omega_rad;  ///< Beard–Maxwell Ω (radians)
    T rho_d;      ///< diffuse BRDF, 1/sr
    T rho_v;      ///< volume BRDF coefficient, 1/sr
};

/// Smallest cosine used in denominators: keeps the model finite at exactly grazing geometry.
inline constexpr double kMinCosine = 1e-7;

/// The parameter-independent part of one (wi, wo) evaluation, precomputed in double.
struct MicrofacetGeometry {
    bool valid = false;                 ///< both directions above the surface
    double cos_i = 0.0, cos_o = 0.0;    ///< clamped to ≥ kMinCosine
    double cos_n = 1.0, tan2_n = 0.0;   ///< facet tilt θN
    double theta_n = 0.0;               ///< θN, radians
    double cos_beta = 1.0, beta = 0.0;  ///< angle of incidence on the facet
    double cot_i = 0.0, cot_o = 0.0;    ///< cotangents of θi, θo (for Smith's Λ)
    double c2i = 1.0, s2i = 0.0;  ///< cos 2αi, sin 2αi: macro → facet frame of the incident beam
    double c2o = 1.0, s2o = 0.0;  ///< cos 2αo, sin 2αo: facet → macro frame of the exitant beam
};

/// Geometry of (wi, wo) in the surface-local frame (pbrdf.h), including the frame rotations.
MicrofacetGeometry microfacet_geometry(const Vec3& wi, const Vec3& wo);

/// The slope falloff exp(−tan²θN / (2σ²)) of D, given 1/(2σ²) (loops over facets compute it once).
template <typename T>
T gaussian_slope_falloff(const T& inv_two_sigma2, double tan2_n) {
    using std::exp;
    return exp(-T(tan2_n) * inv_two_sigma2);
}

/// Gaussian facet-normal density D(θN) (file comment), 1/sr.
template <typename T>
T gaussian_facet_density(const T& sigma, double cos_n, double tan2_n) {
    const T s2 = sigma * sigma;
    const double c4 = cos_n * cos_n * cos_n * cos_n;
    return gaussian_slope_falloff(T(1) / (T(2) * s2), tan2_n) / (T(2.0 * kPi * c4) * s2);
}

/// smith_lambda in double for cot θ ≥ 0, with erfc(a) from Cody's rational functions given the
/// e^(−a²) that Λ needs anyway: glibc's erfc evaluates two more exponentials. erfc's relative error
/// is ≤ 2.2e-16·(8 + a²) (GaussianErfc), and Λ only ever enters 1 + Λ(wi) + Λ(wo).
double smith_lambda_from_gaussian(double sigma, double cot_theta);

/// Smith's Λ for the Gaussian surface at a direction with cotangent `cot_theta` (file comment).
template <typename T>
T smith_lambda(const T& sigma, double cot_theta) {
    using std::erfc;
    using std::exp;
    if constexpr (std::is_same_v<T, double>) {
        if (cot_theta >= 0.0) return smith_lambda_from_gaussian(sigma, cot_theta);
    }
    const T a = T(cot_theta) / (T(std::sqrt(2.0)) * sigma);
    return (exp(-a * a) / (a * T(std::sqrt(kPi))) - erfc(a)) * T(0.5);
}

/// smith_lambda where it is only added to 1: in double precision 0 from a = cotθ/(√2σ) ≥ 6 on,
/// where Λ < e^(−a²)/(a√π) ≤ 2.2e-17 is below half an ulp of 1 (2^−54 ≈ 5.6e-17), so 1 + Λ rounds
/// to exactly 1 and erfc and exp (erfc's own exponentials included) need not be evaluated. Other
/// scalar types (ceres::Jet: derivatives) always take smith_lambda.
template <typename T>
T smith_lambda_beside_one(const T& sigma, double cot_theta) {
    if constexpr (std::is_same_v<T, double>) {
        constexpr double kNegligibleA = 6.0;
        if (cot_theta >= kNegligibleA * std::sqrt(2.0) * sigma) return 0.0;
    }
    return smith_lambda(sigma, cot_theta);
}

/// Beard–Maxwell shadowing/obscuration SO(θN, β; τ, Ω) (file comment), given 1/τ and 1/Ω in 1/rad
/// (loops over facets compute them once).
template <typename T>
T beard_maxwell_shadowing_reciprocal(const T& inv_tau_rad, const T& inv_omega_rad, double theta_n,
                                     double beta) {
    using std::exp;
    const T x = T(theta_n) * inv_omega_rad;
    return (T(1) + x * exp(T(-2.0 * beta) * inv_tau_rad)) / (T(1) + x);
}

/// Beard–Maxwell shadowing/obscuration SO(θN, β; τ, Ω) (file comment), τ and Ω in radians.
template <typename T>
T beard_maxwell_shadowing(const T& tau_rad, const T& omega_rad, double theta_n, double beta) {
    return beard_maxwell_shadowing_reciprocal(T(1) / tau_rad, T(1) / omega_rad, theta_n, beta);
}

/// The full Mueller BRDF (file comment) in 1/sr, given the two factors a sampler has already
/// computed for its pdf: the facet density `d` = gaussian_facet_density(σ, g.cos_n, g.tan2_n) and
/// Smith's `lambda_o` = smith_lambda(σ, g.cot_o). Zero matrix when the geometry is not valid.
template <typename T>
Mueller4<T> shell_target_mueller(const ShellTargetParameters<T>& p, const MicrofacetGeometry& g,
                                 const T& d, const T& lambda_o) {
    Mueller4<T> m;
    if (!g.valid) {
        for (auto& row : m) row.fill(T(0));
        return m;
    }

    const T shadow = T(1) / (T(1) + smith_lambda_beside_one(p.sigma, g.cot_i) + lambda_o);
    const T so = beard_maxwell_shadowing(p.tau_rad, p.omega_rad, g.theta_n, g.beta);
    const T scale = p.bias * d * shadow * so / T(4.0 * g.cos_i * g.cos_o);

    const Mueller4<T> f = fresnel_mueller_t(p.n, p.k, g.cos_beta);
    // M_F = [[a, b, 0, 0], [b, a, 0, 0], [0, 0, re, im], [0, 0, −im, re]] (fresnel.h) and R(α) =
    // [[1,0,0,0],[0,c,s,0],[0,−s,c,0],[0,0,0,1]] (paper eq 11): X = M_F · R(αi) and M = R(αo) · X
    // written out, so that M_F's zero blocks cost no products (the same roundings as the full
    // products, whose terms with a zero factor add exactly 0).
    const T &a = f[0][0], &b = f[0][1], &re = f[2][2], &im = f[2][3];
    const T zero(0);
    const Mueller4<T> x{{{a, b * g.c2i, b * g.s2i, zero},
                         {b, a * g.c2i, a * g.s2i, zero},
                         {zero, -(re * g.s2i), re * g.c2i, im},
                         {zero, im * g.s2i, -(im * g.c2i), re}}};
    m[0] = {a * scale, x[0][1] * scale, x[0][2] * scale, zero};
    m[1] = {(b * g.c2o) * scale, (x[1][1] * g.c2o + x[2][1] * g.s2o) * scale,
            (x[1][2] * g.c2o + x[2][2] * g.s2o) * scale, (im * g.s2o) * scale};
    m[2] = {(-(b * g.s2o)) * scale, (x[2][1] * g.c2o - x[1][1] * g.s2o) * scale,
            (x[2][2] * g.c2o - x[1][2] * g.s2o) * scale, (im * g.c2o) * scale};
    m[3] = {zero, x[3][1] * scale, x[3][2] * scale, re * scale};
    m[0][0] += p.rho_d + T(2) * p.rho_v / T(g.cos_i + g.cos_o);
    return m;
}

/// The full Mueller BRDF (file comment) in 1/sr; zero matrix when the geometry is not valid.
template <typename T>
Mueller4<T> shell_target_mueller(const ShellTargetParameters<T>& p, const MicrofacetGeometry& g) {
    if (!g.valid) return shell_target_mueller(p, g, T(0), T(0));
    return shell_target_mueller(p, g, gaussian_facet_density(p.sigma, g.cos_n, g.tan2_n),
                                smith_lambda(p.sigma, g.cot_o));
}

}  // namespace tirpol::materials

namespace tirpol {
class ConfigNode;
}

namespace tirpol::materials {

class SpectralValue {
public:
    /// A constant.
    SpectralValue(double value =
                      0.0);  // NOLINT(google-explicit-constructor): a number is a constant spectrum
    /// A table; wavelengths strictly increasing (error otherwise, naming `what`).
    SpectralValue(std::vector<double> wavelength_um, std::vector<double> value,
                  const std::string& what);

    /// Reads `node` (a number or a {wavelength_um, value} mapping); values must lie in [lo, hi].
    static SpectralValue from_config(const ConfigNode& node, double lo, double hi);

    /// Value at a wavelength; clamped to the end values outside a table (check `covers` first).
    double at(double wavelength_um) const;
    bool is_constant() const { return m_wavelength_um.empty(); }
    /// True if [lo, hi] lies in the table's range (always for a constant).
    bool covers(double lo_um, double hi_um) const;
    double min_wavelength_um() const;
    double max_wavelength_um() const;

private:
    std::vector<double> m_wavelength_um, m_value;
    double m_constant = 0.0;
};

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
