#pragma once
/// \file pbrdf.h
/// The polarized BRDF interface (paper §2.3). Every model lives in its own file under
/// materials/src/pbrdf/ and implements this interface.
///
/// Surface-local coordinates: z is the surface normal, x and y are tangent; both `wi` (towards
/// where the light comes from) and `wo` (towards the observer) point away from the surface, z > 0.
/// Stokes frames (stokes_frame.h):
///   - incident light travels along −wi; its Stokes vector is given in surface_frame(−wi, z),
///     i.e. reference axis z × (−wi) normalised: the s direction (perpendicular to the plane of
///     incidence);
///   - reflected/emitted light travels along wo; its Stokes vector is in surface_frame(wo, z),
///     reference axis z × wo: the s direction of the plane of reflection/emission.
/// So S1 > 0 means s-polarized on both sides, and for specular geometry the Fresnel Mueller matrix
/// has m01 = (Rs − Rp)/2 > 0. At normal incidence the s direction is a convention
/// (frame_from_reference's fallback); rotationally symmetric models do not depend on it.
///
/// Reciprocity in these frames (tested in tests/materials/reciprocity_test.cpp): exchanging the
/// roles of wi and wo gives M(wo→wi) = Q·M(wi→wo)ᵀ·Q with Q = diag(1, 1, −1, 1).

#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "tirpol/core/geometry.h"
#include "tirpol/core/stokes.h"

namespace tirpol::materials {

/// One importance sample of the incident direction for a given exitant direction.
struct BrdfSample {
    Vec3 wi = Vec3::UnitZ();  ///< sampled incident direction (surface-local, z > 0)
    double pdf = 0.0;  ///< solid-angle density of wi; 0 means "no sample" (weight is then zero)
    MuellerMatrix weight =
        MuellerMatrix::Zero();  ///< M(wi→wo)·cosθi / pdf (for a delta lobe: the reflectance matrix)
    bool is_delta = false;      ///< true for a specular (Dirac) lobe
};

/// A named model parameter, as reported to users and fitted by tirpol::fitting.
struct BrdfParameter {
    std::string name;  ///< e.g. "sigma", "rho_d"
    double value;
    std::string unit;  ///< "" for dimensionless
};

class PolarizedBrdf {
public:
    virtual ~PolarizedBrdf() = default;

    /// Model name as written in material files ("smooth_fresnel", "microfacet", "lambertian").
    virtual std::string model() const = 0;

    /// Mueller BRDF f(wi→wo) in 1/sr at `wavelength_um`, frames as in the file comment. Zero for a
    /// pure delta model (its reflection comes only through `sample`). Never NaN/Inf.
    virtual MuellerMatrix eval(const Vec3& wi, const Vec3& wo, double wavelength_um) const = 0;

    /// Importance-samples wi for the exitant `wo` from two uniform numbers in [0,1).
    virtual BrdfSample sample(const Vec3& wo, double wavelength_um, double u1, double u2) const = 0;

    /// A deterministic map of (u1, u2) for quadratures (emissivity.h): same contract as `sample`
    /// (weight = M·cosθi/pdf with its own pdf, breaks at sample_u1_breaks, the is_isotropic mirror
    /// property), possibly another distribution whose map is smoother in u. Default: `sample`.
    virtual BrdfSample quadrature_sample(const Vec3& wo, double wavelength_um, double u1,
                                         double u2) const {
        return sample(wo, wavelength_um, u1, u2);
    }

    /// Solid-angle pdf of `sample` drawing wi given wo (0 for delta lobes).
    virtual double pdf(const Vec3& wi, const Vec3& wo, double wavelength_um) const = 0;

    /// True if part of the reflection is a Dirac delta (smooth surface).
    virtual bool has_delta() const { return false; }

    /// True if ALL of the reflection is one Dirac delta (sample's weight does not depend on u1,
    /// u2); integrators then need a single sample.
    virtual bool is_pure_delta() const { return false; }

    /// True if the model is isotropic and mirror-symmetric about the plane of wo and the normal,
    /// and `sample` maps u2 to the azimuth 2π·u2 (so u2 and 1 − u2 are mirror images for wo in the
    /// xz plane). The emissivity integrator then integrates half the azimuths; S2 = S3 = 0 exactly.
    virtual bool is_isotropic() const { return false; }

    /// The model's parameters at a wavelength.
    virtual std::vector<BrdfParameter> parameters(double wavelength_um) const = 0;

    /// Values of u1 in (0, 1), increasing, at which `sample` switches from one lobe to the next for
    /// this wo (e.g. specular → diffuse). Deterministic integrators (emissivity.h) split their
    /// quadrature there so that each piece maps smoothly onto directions. Empty: one lobe.
    virtual std::vector<double> sample_u1_breaks(const Vec3& /*wo*/,
                                                 double /*wavelength_um*/) const {
        return {};
    }

    /// Wavelength range (µm) over which the model's tabulated data are defined; eval/sample clamp
    /// to the ends outside it, so callers check it once (EmissivityTable does) before their hot
    /// loops.
    virtual std::pair<double, double> valid_wavelength_range_um() const {
        return {0.0, std::numeric_limits<double>::infinity()};
    }
};

}  // namespace tirpol::materials
