#include "smooth_fresnel.h"

#include "tirpol/materials/fresnel.h"

namespace tirpol::materials {

SmoothFresnelBrdf::SmoothFresnelBrdf(RefractiveIndexTable index) : m_index(std::move(index)) {}

MuellerMatrix SmoothFresnelBrdf::eval(const Vec3& /*wi*/, const Vec3& /*wo*/,
                                      double /*wavelength_um*/) const {
    return MuellerMatrix::Zero();
}

BrdfSample SmoothFresnelBrdf::sample(const Vec3& wo, double wavelength_um, double /*u1*/,
                                     double /*u2*/) const {
    BrdfSample s;
    s.is_delta = true;
    if (!(wo.z() > 0.0)) return s;
    s.wi = Vec3(-wo.x(), -wo.y(), wo.z());
    s.pdf = 1.0;
    // Mirror geometry: surface_frame(−wi, z) and surface_frame(wo, z) share the reference axis z ×
    // wo (also in the normal-incidence fallback), so the Fresnel matrix needs no frame rotation.
    s.weight = fresnel_mueller(m_index.at_clamped(wavelength_um), wo.z());
    return s;
}

double SmoothFresnelBrdf::pdf(const Vec3& /*wi*/, const Vec3& /*wo*/,
                              double /*wavelength_um*/) const {
    return 0.0;
}

std::vector<BrdfParameter> SmoothFresnelBrdf::parameters(double wavelength_um) const {
    const ComplexIndex i = m_index.at_clamped(wavelength_um);
    return {{"n", i.n, ""}, {"k", i.k, ""}};
}

std::pair<double, double> SmoothFresnelBrdf::valid_wavelength_range_um() const {
    return {m_index.min_wavelength_um(), m_index.max_wavelength_um()};
}

}  // namespace tirpol::materials
