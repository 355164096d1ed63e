#include "tirpol/materials/microfacet.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "../gaussian_erfc.h"
#include "../normal_quantile.h"
#include "../sampling.h"
#include "tirpol/core/error.h"
#include "tirpol/materials/fresnel.h"

namespace tirpol::materials {

namespace {
MuellerMatrix to_eigen(const Mueller4<double>& m) {
    MuellerMatrix out;
    for (std::size_t r = 0; r < 4; ++r)
        for (std::size_t c = 0; c < 4; ++c)
            out(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = m[r][c];
    return out;
}
}  // namespace

MicrofacetBrdf::MicrofacetBrdf(MicrofacetParameters parameters)
    : m_parameters(std::move(parameters)) {
    const MicrofacetParameters& p = m_parameters;
    if (p.index.is_constant() && p.sigma.is_constant() && p.bias.is_constant() &&
        p.tau_deg.is_constant() && p.omega_deg.is_constant() && p.rho_d.is_constant() &&
        p.rho_v.is_constant())
        m_constant_parameters = interpolated_parameters(0.0);
}

ShellTargetParameters<double> MicrofacetBrdf::at(double wavelength_um) const {
    return m_constant_parameters ? *m_constant_parameters : interpolated_parameters(wavelength_um);
}

ShellTargetParameters<double> MicrofacetBrdf::interpolated_parameters(double wavelength_um) const {
    const ComplexIndex index = m_parameters.index.at_clamped(wavelength_um);
    return {index.n,
            index.k,
            m_parameters.sigma.at(wavelength_um),
            m_parameters.bias.at(wavelength_um),
            deg_to_rad(m_parameters.tau_deg.at(wavelength_um)),
            deg_to_rad(m_parameters.omega_deg.at(wavelength_um)),
            m_parameters.rho_d.at(wavelength_um),
            m_parameters.rho_v.at(wavelength_um)};
}

MuellerMatrix MicrofacetBrdf::eval(const Vec3& wi, const Vec3& wo, double wavelength_um) const {
    return to_eigen(shell_target_mueller(at(wavelength_um), microfacet_geometry(wi, wo)));
}

namespace {
constexpr double kInvSqrtPi = 0.56418958354775628695;  // 1/√π

/// cot θ for cos θ, capped where θ → 0.
double cotangent(double cos_theta) {
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    return sin_theta * 1e8 <= cos_theta ? 1e8 : cos_theta / sin_theta;
}

/// Smith's Λ of the unit-roughness surface at cot θ = a, with the erfc(a) and e^(−a²) it is made of
/// (the visible-slope sampler's normalisation reuses them: 2·(1 + Λ) = erfc(−a) + e^(−a²)/(a√π)).
/// erfc from the e^(−a²) already at hand (erfc_given_gaussian) saves glibc's two exponentials.
struct SmithTerms {
    double lambda, erfc_a, exp_minus_a2;
};

SmithTerms smith_terms(double sigma, double cot_theta) {
    // From a = 6 on, e^(−a²)/(a√π) ≤ 2.2e-17 bounds Λ, erfc(a) and the visible-slope sampler's
    // e^(−a²)·tanθ/√π alike: each only ever enters a sum with 1 or 2 (1 + Λ, 2 − erfc(a), 1 −
    // erfc(a)/2), which it cannot change (half an ulp of 1 is 5.6e-17), so zeros give the same
    // doubles without erfc and exp (smith_lambda_beside_one, shell_target_math.h).
    if (cot_theta >= 6.0 * std::sqrt(2.0) * sigma) return {0.0, 0.0, 0.0};
    const double a = cot_theta / (std::sqrt(2.0) * sigma);
    const double e = std::exp(-a * a), c = detail::erfc_given_gaussian(a, e);
    return {(e / (a * std::sqrt(kPi)) - c) * 0.5, c, e};
}

/// Slope x̃ ≤ cot θ of a visible facet of the unit-roughness Beckmann surface seen at θ (wo along
/// +x), the root of F(x̃) = u with F(x̃) = (erfc(−x̃) + tanθ/√π·e^(−x̃²)) / (erfc(−cotθ) +
/// tanθ/√π·e^(−cot²θ)) (Heitz & d'Eon 2014, appendix). As in Jakob, "An Improved Visible Normal
/// Sampling Routine for the Beckmann Distribution" (2014; Mitsuba's routine), F is inverted in the
/// erf domain, here written with p = Φ(√2·x̃) = erfc(−x̃)/2: there F = (2p + tanθ/√π·e^(−x̃²))/total
/// is smooth, increasing and concave from 0 to p_max = Φ(√2·cotθ), with dF/dp = 2(1 −
/// x̃·tanθ)/total, and x̃ = Φ⁻¹(p)/√2 costs a rational function (normal_quantile) where erfc cost a
/// rational function and two exponentials. Jakob's fitted guess, erf x̃₀ = erf cotθ − (1 + erf
/// cotθ)(1 − u)^fit, is p₀ = p_max·(1 − (1 − u)^fit); from it Halley steps (the second and third
/// derivatives are the first's factors times e^(x̃²), so a step costs no more than Newton's), kept
/// inside a bisection bracket, reach |F − u| < 1e-13 — checked, or predicted from the step by
/// Halley's error law e' ≈ (F₂²/(4F₁²) − F₃/(6F₁))·e³ (Fₖ the k-th derivative) with a margin of 10
/// — so the map u → x̃ is exact to rounding and smooth. `smith` holds erfc(cot θ) and e^(−cot²θ).
double visible_slope_x(double cos_theta, double u, const SmithTerms& smith) {
    constexpr double kSqrtPi = 1.77245385090551602730, kInvSqrt2 = 0.70710678118654752440;
    constexpr double kFourThirdsSqrtPi = 4.0 / 3.0 * kSqrtPi;
    constexpr double kTolerance = 1e-13;
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    const double tan_theta = sin_theta / cos_theta;
    const double tan_over_sqrt_pi = tan_theta * kInvSqrtPi;
    const double total = (2.0 - smith.erfc_a) + tan_over_sqrt_pi * smith.exp_minus_a2;
    const double inv_total = 1.0 / total;
    const double k = 2.0 * tan_theta * kSqrtPi * inv_total;
    u = std::clamp(u, 1e-16, 1.0 - 1e-16);
    double lo = 0.0, hi = 1.0 - 0.5 * smith.erfc_a;
    // The starting point only, so θ and (1 − u)^fit need not be exact: θ = acos(cos θ) from
    // Abramowitz & Stegun 4.4.45 (|error| < 7e-5 rad), the power in single precision, or to first
    // order in u where that would round to 1.
    const double theta =
        std::sqrt(1.0 - cos_theta) *
        (1.5707288 + cos_theta * (-0.2121144 + cos_theta * (0.0742610 - 0.0187293 * cos_theta)));
    const double fit = 1.0 + theta * (-0.876 + theta * (0.4265 - 0.0594 * theta));
    double p = hi * (u < 1e-3 ? fit * u
                              : 1.0 - std::exp2(static_cast<float>(fit) *
                                                std::log2(static_cast<float>(1.0 - u))));
    for (int i = 0; i < 100; ++i) {
        const double x = detail::normal_quantile(p) * kInvSqrt2;
        const double e = std::exp(-x * x);
        const double f = (2.0 * p + tan_over_sqrt_pi * e) * inv_total - u;
        if (std::abs(f) < kTolerance) return x;
        (f > 0.0 ? hi : lo) = p;
        // F₁ = d1, F₂ = −k/e and F₃ = −2√π·x·k/e², with k = 2·tanθ·√π/total (the derivatives of x̃
        // bring √π·e^(x̃²) = √π/e each); the step and the error law below are multiplied through by
        // powers of e so that neither divides by e: one division per step.
        const double d1 = 2.0 * (1.0 - x * tan_theta) * inv_total;
        double next = p - 2.0 * f * d1 * e / (2.0 * d1 * d1 * e + f * k);
        if (!(next > lo && next < hi)) {
            next = 0.5 * (lo + hi);
        } else if (std::abs(f) < 1e-4) {
            // |F₁·(F₂²/(4F₁²) − F₃/(6F₁))·step³| < tol/10, times 4·|F₁|·e²: no division.
            const double step = std::abs(next - p);
            if (k * std::abs(k + kFourThirdsSqrtPi * x * d1) * (step * step * step) <
                0.4 * kTolerance * std::abs(d1) * (e * e))
                return detail::normal_quantile(next) * kInvSqrt2;
        }
        if (next == p) break;
        p = next;
    }
    return detail::normal_quantile(p) * kInvSqrt2;
}

/// sample_visible_normal given Smith's terms at wo's (unstretched) cot θo (smith_terms): the
/// stretched direction's cotangent is cot θo/α, which is the same a.
Vec3 sample_visible_normal(const Vec3& wo, double sigma, double u1, double u2,
                           const SmithTerms& smith) {
    // Heitz & d'Eon, "Importance sampling microfacet-based BSDFs using the distribution of visible
    // normals", EGSR 2014, §4: the Gaussian slopes are Beckmann's with α = √2σ; stretch wo to unit
    // roughness, sample the visible slopes there, rotate to wo's azimuth, unstretch.
    const double alpha = std::sqrt(2.0) * sigma;
    const Vec3 stretched = Vec3(alpha * wo.x(), alpha * wo.y(), wo.z()).normalized();
    double x, y;
    if (stretched.z() > 0.99999999) {  // seen from the normal: the plain slope distribution
        const double r = std::sqrt(-std::log1p(-std::min(u1, 1.0 - 1e-16)));
        x = r * std::cos(2.0 * kPi * u2);
        y = r * std::sin(2.0 * kPi * u2);
    } else {
        // The slope across wo's azimuth is Gaussian: erf⁻¹(2u − 1) = Φ⁻¹(u)/√2.
        const double slope_x = visible_slope_x(stretched.z(), u1, smith),
                     slope_y = detail::normal_quantile(std::clamp(u2, 1e-16, 1.0 - 1e-16)) *
                               0.70710678118654752440;
        const double r = std::sqrt(stretched.x() * stretched.x() + stretched.y() * stretched.y());
        const double c = stretched.x() / r, s = stretched.y() / r;
        x = c * slope_x - s * slope_y;
        y = s * slope_x + c * slope_y;
    }
    return Vec3(-alpha * x, -alpha * y, 1.0).normalized();
}
}  // namespace

Vec3 sample_visible_normal(const Vec3& wo, double sigma, double u1, double u2) {
    return sample_visible_normal(wo, sigma, u1, u2, smith_terms(sigma, cotangent(wo.z())));
}

namespace {
// Probability of drawing from the specular lobe for the exitant direction with cosine `cos_o`: the
// lobes' share of the reflected energy. The specular share uses the Fresnel reflectance at the
// exitant angle, not at normal incidence: at grazing views a glossy surface reflects mostly
// specularly, and starving that lobe there made polarized sky reflections arrive as rare, heavy
// samples (salt-and-pepper S1 on car roofs, the paper's §4.3 artifact).
double specular_probability(const ShellTargetParameters<double>& p, double cos_o) {
    // Hemispherical albedo of the diffuse term (π ρ_D) and of the volume term at normal incidence
    // (4π ρ_V (1 − ln 2)).
    const double diffuse = kPi * p.rho_d + 4.0 * kPi * (1.0 - std::log(2.0)) * p.rho_v;
    if (diffuse <= 0.0) return 1.0;
    const FresnelReflectances<double> r = fresnel_reflectances(
        TinyComplex<double>{p.n * p.n - p.k * p.k, 2.0 * p.n * p.k}, std::clamp(cos_o, 0.0, 1.0));
    const double specular = std::min(1.0, p.bias * 0.5 * (r.rs2 + r.rp2));
    if (specular <= 0.0) return 0.0;
    // A defensive mixture (Hesterberg 1995): each lobe keeps at least a quarter of the samples, so
    // its MIS weight is at most 4× and, with the sampler's strata of a quarter (4 points per
    // replicate, or a multiple), every replicate draws each lobe a fixed number of times. A lobe
    // drawn by ~1 sample in 11 (glossy paint at grazing views) made replicates that missed it
    // alike, their spread blind to it.
    return std::clamp(specular / (specular + diffuse), 0.25, 0.75);
}

/// How the specular lobe draws its facet normal: from the normals visible from wo (the renderer's
/// sampler) or from D(h)·cosθh (the smoother map in u that the emissivity quadrature integrates
/// through).
enum class FacetSampling { visible, slope };

/// The mirror image of `w` in the tangent plane.
Vec3 folded(const Vec3& w) { return Vec3(w.x(), w.y(), -w.z()); }

/// Density of the visible-normal reflection wi = 2(h·wo)h − wo at a wi below the horizon (given as
/// its folded image `wi_below`), which the sampler folds back up; `lambda_o` is Smith's Λ(wo).
double masked_reflection_pdf(double sigma, const Vec3& wi_below, const Vec3& wo, double cos_o,
                             double lambda_o) {
    // The half vector's signs are those of the unnormalised sum: about half the samples (wi above
    // wo's elevation) have no folded image, and are told so before the normalisation and D's
    // exponential.
    const Vec3 sum = wi_below + wo;
    if (!(sum.z() > 0.0) || !(sum.dot(wo) > 0.0)) return 0.0;
    const Vec3 h = sum.normalized();
    if (!(h.dot(wo) > 0.0) || !(h.z() > 0.0)) return 0.0;
    const double cos_h = std::max(h.z(), kMinCosine);
    const double tan2 = (1.0 - cos_h * cos_h) / (cos_h * cos_h);
    return gaussian_facet_density(sigma, cos_h, tan2) / ((1.0 + lambda_o) * 4.0 * cos_o);
}

/// The mixture's pdf at the geometry `g` of (wi, wo), given the facet density `d` at g's half
/// vector and Smith's Λ(wo), which the weight needs too (computed once per sample).
double mixture_pdf(double sigma, double p_spec, const Vec3& wi, const Vec3& wo,
                   const MicrofacetGeometry& g, double d, double lambda_o, FacetSampling facets) {
    if (!g.valid) return 0.0;
    double pdf = 0.0;
    if (p_spec > 0.0) {
        // The reflection wi = 2(h·wo)h − wo has Jacobian 1/(4 h·wo) (Walter et al., EGSR 2007, eq
        // 14). Visible normals have density G1(wo)·D(h)·(h·wo)/cosθo (Heitz & d'Eon 2014, eq 2), so
        // the h·wo cancel; slope sampling has D·cosθh (Torrance & Sparrow 1967); h·wo = h·wi = cos
        // β.
        if (facets == FacetSampling::visible) {
            pdf += p_spec * d / ((1.0 + lambda_o) * 4.0 * g.cos_o);
            // A visible normal whose reflection points below the horizon is folded up
            // (sample_mixture), so wi is also drawn through its mirror image.
            pdf += p_spec * masked_reflection_pdf(sigma, folded(wi), wo, g.cos_o, lambda_o);
        } else if (g.cos_beta > 0.0) {
            pdf += p_spec * d * g.cos_n / (4.0 * g.cos_beta);
        }
    }
    if (p_spec < 1.0) pdf += (1.0 - p_spec) * g.cos_i / kPi;
    return pdf;
}

double mixture_pdf(const ShellTargetParameters<double>& p, double p_spec, const Vec3& wi,
                   const Vec3& wo, FacetSampling facets) {
    const MicrofacetGeometry g = microfacet_geometry(wi, wo);
    if (!g.valid) return 0.0;
    return mixture_pdf(p.sigma, p_spec, wi, wo, g,
                       gaussian_facet_density(p.sigma, g.cos_n, g.tan2_n),
                       smith_lambda(p.sigma, g.cot_o), facets);
}

BrdfSample sample_mixture(const ShellTargetParameters<double>& p, double p_spec, const Vec3& wo,
                          double u1, double u2, FacetSampling facets) {
    BrdfSample s;
    if (!(wo.z() > 0.0)) return s;
    // Λ(wo) enters the visible-normal sampler's normalisation, its pdf and the BRDF's G: computed
    // once.
    const SmithTerms smith = smith_terms(p.sigma, cotangent(wo.z()));
    if (u1 < p_spec) {
        const double u = u1 / p_spec;
        Vec3 h;
        if (facets == FacetSampling::visible) {
            h = sample_visible_normal(wo, p.sigma, u, u2, smith);
        } else {  // inverse CDF of the slope distribution: tan²θh = −2σ² ln(1 − u)
            const double tan2 = -2.0 * p.sigma * p.sigma * std::log1p(-std::min(u, 1.0 - 1e-16));
            const double cos_h = 1.0 / std::sqrt(1.0 + tan2);
            const double sin_h = std::sqrt(std::max(0.0, 1.0 - cos_h * cos_h));
            h = Vec3(sin_h * std::cos(2.0 * kPi * u2), sin_h * std::sin(2.0 * kPi * u2), cos_h);
        }
        const double ho = h.dot(wo);
        if (!(ho > 0.0)) return s;
        s.wi = (2.0 * ho * h - wo).normalized();
        // A reflection below the horizon (masked: the model's G is 0 there) would be a wasted,
        // zero-weight sample: at grazing views 3–7 % of visible normals give one, a rare event that
        // a pixel's few samples can miss altogether, leaving its variance estimate blind to it.
        // Folding it into the upper hemisphere keeps every sample and stays unbiased, as
        // mixture_pdf counts both images.
        if (facets == FacetSampling::visible && s.wi.z() < 0.0) s.wi = folded(s.wi);
        if (!(s.wi.z() > 0.0)) return s;
    } else {
        const double u = (u1 - p_spec) / (1.0 - p_spec);
        s.wi = detail::sample_cosine_hemisphere(u, u2);
    }
    const MicrofacetGeometry g = microfacet_geometry(s.wi, wo);
    if (!g.valid) return s;
    // D(h) is in both the pdf and the BRDF: one exponential.
    const double d = gaussian_facet_density(p.sigma, g.cos_n, g.tan2_n);
    s.pdf = mixture_pdf(p.sigma, p_spec, s.wi, wo, g, d, smith.lambda, facets);
    if (!(s.pdf > 0.0) || !std::isfinite(s.pdf)) {
        s.pdf = 0.0;
        return s;
    }
    const Mueller4<double> m = shell_target_mueller(p, g, d, smith.lambda);
    const double factor = s.wi.z() / s.pdf;
    for (std::size_t r = 0; r < 4; ++r)
        for (std::size_t c = 0; c < 4; ++c)
            s.weight(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = m[r][c] * factor;
    return s;
}
}  // namespace

double MicrofacetBrdf::specular_sampling_probability(const Vec3& wo, double wavelength_um) const {
    return specular_probability(at(wavelength_um), wo.z());
}

BrdfSample MicrofacetBrdf::sample(const Vec3& wo, double wavelength_um, double u1,
                                  double u2) const {
    const ShellTargetParameters<double> p = at(wavelength_um);
    return sample_mixture(p, specular_probability(p, wo.z()), wo, u1, u2, FacetSampling::visible);
}

BrdfSample MicrofacetBrdf::quadrature_sample(const Vec3& wo, double wavelength_um, double u1,
                                             double u2) const {
    const ShellTargetParameters<double> p = at(wavelength_um);
    return sample_mixture(p, specular_probability(p, wo.z()), wo, u1, u2, FacetSampling::slope);
}

double MicrofacetBrdf::pdf(const Vec3& wi, const Vec3& wo, double wavelength_um) const {
    const ShellTargetParameters<double> p = at(wavelength_um);
    return mixture_pdf(p, specular_probability(p, wo.z()), wi, wo, FacetSampling::visible);
}

std::vector<double> MicrofacetBrdf::sample_u1_breaks(const Vec3& wo, double wavelength_um) const {
    const double p = specular_sampling_probability(wo, wavelength_um);
    if (p > 0.0 && p < 1.0) return {p};
    return {};
}

std::vector<BrdfParameter> MicrofacetBrdf::parameters(double wavelength_um) const {
    const ShellTargetParameters<double> p = at(wavelength_um);
    return {{"n", p.n, ""},
            {"k", p.k, ""},
            {"sigma", p.sigma, ""},
            {"bias", p.bias, ""},
            {"tau", rad_to_deg(p.tau_rad), "deg"},
            {"omega", rad_to_deg(p.omega_rad), "deg"},
            {"rho_d", p.rho_d, "1/sr"},
            {"rho_v", p.rho_v, "1/sr"}};
}

std::pair<double, double> MicrofacetBrdf::valid_wavelength_range_um() const {
    double lo = m_parameters.index.min_wavelength_um(), hi = m_parameters.index.max_wavelength_um();
    for (const SpectralValue* v :
         {&m_parameters.sigma, &m_parameters.bias, &m_parameters.tau_deg, &m_parameters.omega_deg,
          &m_parameters.rho_d, &m_parameters.rho_v}) {
        lo = std::max(lo, v->min_wavelength_um());
        hi = std::min(hi, v->max_wavelength_um());
    }
    return {lo, hi};
}

}  // namespace tirpol::materials
