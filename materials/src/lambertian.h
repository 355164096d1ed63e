#pragma once
/// \file lambertian.h
/// Lambertian (perfectly diffuse, unpolarized) reflector: M = (ρ/π)·diag(1, 0, 0, 0), where ρ is
/// the directional-hemispherical reflectance (Lambert 1760; Nicodemus et al., NBS Monograph 160,
/// 1977). Its emissivity is unpolarized and angle-independent: ε = 1 − ρ.

#include "tirpol/materials/microfacet.h"
#include "tirpol/materials/pbrdf.h"

namespace tirpol::materials {

class LambertianBrdf final : public PolarizedBrdf {
public:
    /// `reflectance` in [0, 1] (constant or per wavelength).
    explicit LambertianBrdf(SpectralValue reflectance);

    std::string model() const override { return "lambertian"; }
    MuellerMatrix eval(const Vec3& wi, const Vec3& wo, double wavelength_um) const override;
    /// Cosine-weighted hemisphere sampling (pdf = cosθi/π), Malley's method.
    BrdfSample sample(const Vec3& wo, double wavelength_um, double u1, double u2) const override;
    double pdf(const Vec3& wi, const Vec3& wo, double wavelength_um) const override;
    bool is_isotropic() const override { return true; }
    std::vector<BrdfParameter> parameters(double wavelength_um) const override;
    std::pair<double, double> valid_wavelength_range_um() const override;

private:
    SpectralValue m_reflectance;
};

}  // namespace tirpol::materials
