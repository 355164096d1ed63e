#pragma once
/// \file smooth_fresnel.h
/// Optically smooth interface: a Dirac specular lobe whose Mueller matrix is the Fresnel reflection
/// matrix (fresnel.h) at θi = θo. Its emissivity is ε = e0 − M_F(θ)·e0 = (1 − R, −(Rs − Rp)/2, 0,
/// 0): emission polarized in the plane of emission (S1 < 0), the classic result of Sandus, Appl.
/// Opt. 4, 1634 (1965).

#include "tirpol/materials/fresnel.h"
#include "tirpol/materials/pbrdf.h"

namespace tirpol::materials {

class SmoothFresnelBrdf final : public PolarizedBrdf {
public:
    explicit SmoothFresnelBrdf(RefractiveIndexTable index);

    std::string model() const override { return "smooth_fresnel"; }
    /// Zero: a delta lobe has no finite BRDF value (reflection comes through `sample`).
    MuellerMatrix eval(const Vec3& wi, const Vec3& wo, double wavelength_um) const override;
    /// The mirror direction with weight = Fresnel Mueller matrix, is_delta = true, pdf = 1 (a
    /// discrete probability, by the pbrt convention for delta lobes).
    BrdfSample sample(const Vec3& wo, double wavelength_um, double u1, double u2) const override;
    double pdf(const Vec3& wi, const Vec3& wo, double wavelength_um) const override;
    bool has_delta() const override { return true; }
    bool is_pure_delta() const override { return true; }
    bool is_isotropic() const override { return true; }
    std::vector<BrdfParameter> parameters(double wavelength_um) const override;
    std::pair<double, double> valid_wavelength_range_um() const override;

    const RefractiveIndexTable& index() const { return m_index; }

private:
    RefractiveIndexTable m_index;
};

}  // namespace tirpol::materials
