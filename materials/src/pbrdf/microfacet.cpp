#include "tirpol/materials/microfacet.h"

#include <algorithm>
#include <cmath>

#include "../sampling.h"
#include "tirpol/core/error.h"
#include "tirpol/materials/fresnel.h"

namespace tirpol::materials {

namespace {
MuellerMatrix to_eigen(const Mueller4<double>& m) {
    MuellerMatrix out;
    for (std::size_t r = 0; r < 4; ++r)
        for (std::size_t c = 0; c < 4; ++c) out(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = m[r][c];
    return out;
}
}  // namespace

MicrofacetBrdf::MicrofacetBrdf(MicrofacetParameters parameters) : m_parameters(std::move(parameters)) {}

ShellTargetParameters<double> MicrofacetBrdf::at(double wavelength_um) const {
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
// Probability of drawing from the specular lobe for the exitant direction with cosine `cos_o`: the
// lobes' share of the reflected energy. The specular share uses the Fresnel reflectance at the
// exitant angle, not at normal incidence: at grazing views a glossy surface reflects mostly
// specularly, and starving that lobe there made polarized sky reflections arrive as rare, heavy
// samples (salt-and-pepper S1 on car roofs, the paper's §4.3 artifact).
double specular_probability(const ShellTargetParameters<double>& p, double cos_o) {
    const double specular = std::min(1.0, p.bias * fresnel({p.n, p.k}, std::clamp(cos_o, 0.0, 1.0)).R());
    // Hemispherical albedo of the diffuse term (π ρ_D) and of the volume term at normal incidence
    // (4π ρ_V (1 − ln 2)).
    const double diffuse = kPi * p.rho_d + 4.0 * kPi * (1.0 - std::log(2.0)) * p.rho_v;
    if (diffuse <= 0.0) return 1.0;
    if (specular <= 0.0) return 0.0;
    // Keep both lobes sampled so that neither estimator is starved.
    return std::clamp(specular / (specular + diffuse), 0.05, 0.95);
}

double mixture_pdf(const ShellTargetParameters<double>& p, double p_spec, const Vec3& wi, const Vec3& wo) {
    if (!(wi.z() > 0.0) || !(wo.z() > 0.0)) return 0.0;
    double pdf = 0.0;
    if (p_spec > 0.0) {
        const Vec3 h = (wi + wo).normalized();
        const double ho = h.dot(wo);
        if (ho > 0.0) {
            const double cos_h = std::max(h.z(), kMinCosine);
            const double tan2 = (1.0 - cos_h * cos_h) / (cos_h * cos_h);
            const double d = gaussian_facet_density(p.sigma, cos_h, tan2);
            // Density of h is D·cosθh; the reflection wi = 2(h·wo)h − wo has Jacobian 1/(4 h·wo)
            // (Torrance & Sparrow 1967; Walter et al., EGSR 2007, eq 14).
            pdf += p_spec * d * cos_h / (4.0 * ho);
        }
    }
    if (p_spec < 1.0) pdf += (1.0 - p_spec) * detail::cosine_hemisphere_pdf(wi);
    return pdf;
}
}  // namespace

double MicrofacetBrdf::specular_sampling_probability(const Vec3& wo, double wavelength_um) const {
    return specular_probability(at(wavelength_um), wo.z());
}

BrdfSample MicrofacetBrdf::sample(const Vec3& wo, double wavelength_um, double u1, double u2) const {
    BrdfSample s;
    if (!(wo.z() > 0.0)) return s;
    const ShellTargetParameters<double> p = at(wavelength_um);
    const double p_spec = specular_probability(p, wo.z());
    if (u1 < p_spec) {
        const double u = u1 / p_spec;
        const double sigma = p.sigma;
        const double tan2 = -2.0 * sigma * sigma * std::log1p(-std::min(u, 1.0 - 1e-16));
        const double cos_h = 1.0 / std::sqrt(1.0 + tan2);
        const double sin_h = std::sqrt(std::max(0.0, 1.0 - cos_h * cos_h));
        const double phi = 2.0 * kPi * u2;
        const Vec3 h(sin_h * std::cos(phi), sin_h * std::sin(phi), cos_h);
        const double ho = h.dot(wo);
        if (!(ho > 0.0)) return s;
        s.wi = 2.0 * ho * h - wo;
        if (!(s.wi.z() > 0.0)) return s;
        s.wi.normalize();
    } else {
        const double u = (u1 - p_spec) / (1.0 - p_spec);
        s.wi = detail::sample_cosine_hemisphere(u, u2);
    }
    s.pdf = mixture_pdf(p, p_spec, s.wi, wo);
    if (!(s.pdf > 0.0) || !std::isfinite(s.pdf)) {
        s.pdf = 0.0;
        return s;
    }
    s.weight = to_eigen(shell_target_mueller(p, microfacet_geometry(s.wi, wo))) * (s.wi.z() / s.pdf);
    return s;
}

double MicrofacetBrdf::pdf(const Vec3& wi, const Vec3& wo, double wavelength_um) const {
    const ShellTargetParameters<double> p = at(wavelength_um);
    return mixture_pdf(p, specular_probability(p, wo.z()), wi, wo);
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
    for (const SpectralValue* v : {&m_parameters.sigma, &m_parameters.bias, &m_parameters.tau_deg,
                                   &m_parameters.omega_deg, &m_parameters.rho_d, &m_parameters.rho_v}) {
        lo = std::max(lo, v->min_wavelength_um());
        hi = std::min(hi, v->max_wavelength_um());
    }
    return {lo, hi};
}

}  // namespace tirpol::materials
