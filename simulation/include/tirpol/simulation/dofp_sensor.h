#pragma once
/// \file dofp_sensor.h
/// A division-of-focal-plane (microgrid) polarization camera as the renderer's sensor stage: every
/// pixel of a full-resolution rendered Stokes image (camera frame of ARCHITECTURE.md, band radiance
/// W/(m²·sr)) is seen through that pixel's own micro-polarizer and bolometer,
///
///   counts_i = R_i·½·t_i·(S0_i + d_i·(S1_i cos 2θ_i + S2_i sin 2θ_i)) + o_i + noise,
///
/// θ_i the micro-polarizer's axis (the pattern's nominal angle at the pixel's 2×2 cell position
/// plus a manufacturing error), d_i its diattenuation, t_i = τ_max + τ_min its transmission for
/// unpolarized light (1 for an ideal polarizer; Chipman, Lam & Young 2018 eq 6.35), R_i the
/// bolometer's responsivity and o_i its offset (the non-uniformity a two-point NUC removes). The
/// manufacturing spread is drawn once per pixel from a seed (S. B. Powell & V. Gruev, Opt. Express
/// 21(18), 21039, 2013: filter properties vary by up to 20 % across an array).
///
/// The instantaneous-field-of-view (IFOV) error is not modelled here: it comes from the rendering,
/// because pixel i reads only S_i, the mean over its own footprint that the renderer traced at the
/// sensor's full resolution. The four analyzers of a 2×2 cell therefore see four different places,
/// as on a real focal plane.

#include <array>
#include <cstdint>
#include <vector>

#include "tirpol/core/config.h"
#include "tirpol/core/image.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::simulation {

/// How the micro-polarizers and bolometers of one array differ from each other (1σ spreads).
struct DofpManufacturingSpread {
    double axis_sigma_deg = 1.0;       ///< θ_i = nominal + N(0, σ)
    double diattenuation_mean = 0.95;  ///< d_i = mean + N(0, σ), clipped to [0, 1]
    double diattenuation_sigma = 0.015;
    double transmission_mean = 0.9;  ///< t_i = mean·(1 + N(0, σ_rel)), clipped to ≥ 0
    double transmission_rel_sigma = 0.05;
    double responsivity_rel_sigma = 0.05;  ///< R_i = mean·(1 + N(0, σ_rel))
    double offset_sigma_counts = 150.0;    ///< o_i = mean + N(0, σ)
};

struct DofpSensorSpec {
    /// Nominal analyzer angles (degrees, camera frame) at cell positions (row, col) = (y mod 2,
    /// x mod 2) in the order (0,0), (0,1), (1,0), (1,1). Default: the Sony IMX250MZR layout.
    std::array<double, 4> pattern_deg{90.0, 45.0, 135.0, 0.0};
    DofpManufacturingSpread spread;
    double responsivity_counts_per_radiance = 800.0;  ///< mean R, counts per W/(m²·sr)
    double offset_counts = 3000.0;                    ///< mean o
    /// Temporal noise as the NEDT of an average pixel for unpolarized light at
    /// `reference_temperature_k`: σ = R·½·t̄·NEDT·dL/dT (0: noiseless).
    double nedt_k = 0.05;
    double reference_temperature_k = 300.0;
    int bits_per_pixel = 16;  ///< the ADC: counts are rounded and clipped to [0, 2^bits − 1]
    std::uint64_t seed = 1;   ///< the array's manufacturing draw; frames' noise adds their index

    /// From a YAML mapping with optional `pattern_deg`, `spread` (the fields above),
    /// `responsivity_counts_per_radiance`, `offset_counts`, `nedt_k`, `reference_temperature`,
    /// `bits_per_pixel`, `seed` (docs/microgrid.md). Throws tirpol::Error naming the field.
    static DofpSensorSpec from_config(const ConfigNode& node);
    /// Throws tirpol::Error (prefixed by `context`) for a pattern that is not four distinct
    /// finite angles in [0°, 180°), a negative spread, or a value out of its physical range.
    void validate(const std::string& context) const;
};

/// The planted truth of every pixel (row-major planes, width × height).
struct DofpPixels {
    int width = 0, height = 0;
    std::vector<double> axis_deg;       ///< θ_i
    std::vector<double> diattenuation;  ///< d_i
    std::vector<double> transmission;   ///< t_i
    std::vector<double> responsivity;   ///< R_i, counts per W/(m²·sr)
    std::vector<double> offset_counts;  ///< o_i

    /// The analysis vector in counts per W/(m²·sr): g_i·(1, d_i cos 2θ_i, d_i sin 2θ_i) with
    /// g_i = R_i·½·t_i — the form calibration's per-pixel calibration fits.
    std::array<double, 3> analysis(std::size_t i) const;
};

class DofpSensor {
public:
    /// Draws the array's pixels from `spec.seed` (the same array for the same spec and size).
    /// Throws tirpol::Error for a bad spec or a size that is not even and ≥ 2.
    DofpSensor(DofpSensorSpec spec, int width, int height, Band band);

    const DofpSensorSpec& spec() const { return m_spec; }
    const DofpPixels& pixels() const { return m_pixels; }
    int width() const { return m_pixels.width; }
    int height() const { return m_pixels.height; }
    /// Temporal noise of one frame, counts.
    double noise_sigma_counts() const { return m_noise_sigma_counts; }
    /// Nominal analyzer angle of pixel (x, y), degrees.
    double nominal_angle_deg(int x, int y) const;

    /// Noise-free counts (not rounded) of a Stokes image (channels S0 S1 S2, band radiance, the
    /// sensor's size; S3 is not seen by linear analyzers), row-major. Throws tirpol::Error for
    /// another size or a missing channel.
    std::vector<float> expected_counts(const Image& stokes) const;
    /// One raw frame as the camera reads it out: expected counts plus temporal noise (realisation
    /// `frame_index`, a pure function of seed, frame and pixel), rounded and clipped by the ADC.
    /// Channel `counts`; attributes microgrid_pattern_deg, frame_index, counts_noise_sigma, units.
    Image frame(const Image& stokes, std::uint64_t frame_index) const;

private:
    DofpSensorSpec m_spec;
    DofpPixels m_pixels;
    Band m_band;
    double m_noise_sigma_counts = 0.0;
};

}  // namespace tirpol::simulation
