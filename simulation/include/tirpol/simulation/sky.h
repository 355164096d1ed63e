#pragma once
/// \file sky.h
/// Downwelling sky radiance for rays that leave the scene, and the sun. The sky is unpolarized
/// (a clear LWIR night sky is, to first order; the paper's MODTRAN-P polarized sky is not
/// modelled).

#include <memory>
#include <optional>
#include <vector>

#include "tirpol/core/config.h"
#include "tirpol/core/geometry.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::simulation {

class SkyModel;

/// Sky radiance as a grey-body ε(θ)·L_bb(λ, T(θ)) of zenith angle θ. The sky types are registered
/// by name, one file each in simulation/src/skies/ (docs/scene-format.md):
///  - uniform: ε = 1 at one temperature (or the brightness temperature of a given band radiance);
///  - clear_sky: effective emissivity ε(θ) = 1 − (1 − ε_zenith)^(1/cos θ) at the air temperature
///    (Granqvist & Hjortsberg 1981; ε_zenith from the scene or a clear-sky model of the thermal
///    module);
///  - table: band radiance vs zenith angle from a CSV (e.g. converted from MODTRAN or libRadtran),
///    turned into brightness temperatures over the band and interpolated linearly in zenith angle.
/// Below the horizon every type takes its horizon value (ε → 1 for the clear sky).
class Sky {
public:
    /// A uniform sky at 0 K (no radiance), until a scene sets one.
    Sky();
    /// The sky of `model`, a registered sky type (simulation/src/sky_model.h).
    explicit Sky(std::shared_ptr<const SkyModel> model);

    static Sky uniform(double temperature_k);
    static Sky clear_sky(double air_temperature_k, double zenith_emissivity);
    static Sky table(std::vector<double> zenith_deg, std::vector<double> band_radiance,
                     const Band& band);

    /// From the `sky:` mapping of a scene file, by its `type` (an unknown type fails at `type`
    /// listing the registered ones); `band` converts band radiances to brightness temperatures.
    static Sky from_config(const ConfigNode& node, const Band& band);

    /// Spectral radiance, W/(m²·sr·µm), seen along the world direction `direction` (pointing to the
    /// sky).
    double spectral_radiance(double wavelength_um, const Vec3& direction) const;

    /// The sky at one wavelength with Planck's law evaluated once where the temperature does not
    /// depend on the direction (uniform and clear skies): what a renderer keeps per wavelength
    /// node.
    class AtWavelength {
    public:
        /// Sky::spectral_radiance(wavelength_um, direction), W/(m²·sr·µm), to rounding (the
        /// model's per-path emissivity, e.g. the clear sky's with its logarithm taken once).
        double spectral_radiance(const Vec3& direction) const;

    private:
        friend class Sky;
        const SkyModel* m_model = nullptr;
        double m_wavelength_um = 0.0;
        bool m_isothermal = false;  ///< the temperature does not depend on the direction
        double m_blackbody = 0.0;   ///< L_bb(λ, T) when m_isothermal
    };
    /// The sky at `wavelength_um`; refers to this Sky's model, which must outlive it.
    AtWavelength at_wavelength(double wavelength_um) const;

    /// Effective emissivity and temperature at zenith angle θ given by cos θ.
    double emissivity(double cos_zenith) const;
    double temperature_k(double cos_zenith) const;

private:
    std::shared_ptr<const SkyModel> m_model;
};

/// The sun as a uniform disk of solid angle `solid_angle_sr` and spectral radiance
/// transmittance·L_bb(λ, temperature_k). Defaults: 5778 K, 6.8e-5 sr (angular radius 0.2666°).
struct Sun {
    Vec3 direction = Vec3::UnitZ();  ///< unit world vector pointing to the sun
    double temperature_k = 5778.0;
    double solid_angle_sr = 6.8e-5;
    double transmittance = 1.0;  ///< atmospheric path transmittance (grey)

    /// From the `sun:` mapping: `elevation_deg`/`azimuth_deg` (azimuth from north, clockwise toward
    /// east) or `direction`, and `temperature_k` (+ `transmittance`) or a band `radiance` in
    /// W/(m²·sr).
    static Sun from_config(const ConfigNode& node, const Band& band);

    double spectral_radiance(double wavelength_um) const;
    /// cos of the disk's angular radius: a direction d is on the disk when d·direction ≥ this.
    double cos_angular_radius() const { return 1.0 - solid_angle_sr / (2.0 * kPi); }
};

}  // namespace tirpol::simulation
