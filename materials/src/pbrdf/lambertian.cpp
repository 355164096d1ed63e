#include "lambertian.h"

#include "../sampling.h"
#include "tirpol/core/error.h"

namespace tirpol::materials {

LambertianBrdf::LambertianBrdf(SpectralValue reflectance) : m_reflectance(std::move(reflectance)) {}

MuellerMatrix LambertianBrdf::eval(const Vec3& wi, const Vec3& wo, double wavelength_um) const {
    MuellerMatrix m = MuellerMatrix::Zero();
    if (wi.z() > 0.0 && wo.z() > 0.0) m(0, 0) = m_reflectance.at(wavelength_um) / kPi;
    return m;
}

BrdfSample LambertianBrdf::sample(const Vec3& wo, double wavelength_um, double u1,
                                  double u2) const {
    BrdfSample s;
    s.wi = detail::sample_cosine_hemisphere(u1, u2);
    s.pdf = detail::cosine_hemisphere_pdf(s.wi);
    if (s.pdf > 0.0 && wo.z() > 0.0)
        s.weight(0, 0) = m_reflectance.at(wavelength_um);  // f·cos/pdf = ρ
    return s;
}

double LambertianBrdf::pdf(const Vec3& wi, const Vec3& wo, double /*wavelength_um*/) const {
    return wo.z() > 0.0 ? detail::cosine_hemisphere_pdf(wi) : 0.0;
}

std::vector<BrdfParameter> LambertianBrdf::parameters(double wavelength_um) const {
    return {{"reflectance", m_reflectance.at(wavelength_um), ""}};
}

std::pair<double, double> LambertianBrdf::valid_wavelength_range_um() const {
    return {m_reflectance.min_wavelength_um(), m_reflectance.max_wavelength_um()};
}

}  // namespace tirpol::materials
