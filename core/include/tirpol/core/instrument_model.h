#pragma once
/// \file instrument_model.h
/// The forward model of the field instrument — a camera behind a rotating, tilted wire-grid
/// polarizer (paper §3.1) — shared by everything that predicts counts from radiance: simulation's
/// sensor model, calibration's synthetic sessions and the digital twin (which uses the sensor
/// model).
///
/// Band radiance on the detector with the polarizer at angle α (W/(m²·sr)):
///   L(α) = v · [P(α + δ) · S]₀ + B(α),   B(α) = ρ · L_r · (1 + p · cos 2α) + ε · L_grid
/// P is a linear diattenuator of major transmittance τ and extinction ratio τ/τ_min (Chipman, Lam &
/// Young 2018 eq 6.35, core polarizer_with_extinction), δ the mount's angle offset, v a per-pixel
/// transmission factor (vignetting; 1 without), S the scene's Stokes vector in the camera frame of
/// ARCHITECTURE.md. B is what the tilted grid adds: its reflection of the scene behind the camera
/// (the cold sky, band radiance L_r), partly polarized across the wires (p), and its own emission
/// (ε · L_grid, L_grid the band radiance of a blackbody at the grid's temperature).
/// Counts: C = o + g · L + σ · u, with per-pixel gain g (counts per W/(m²·sr)), offset o, temporal
/// noise σ (counts) and u a standard-normal deviate the caller draws from its own stream.

#include "tirpol/core/stokes.h"

namespace tirpol {

struct WireGridPolarizer {
    double transmission = 0.7;             ///< τ, major-axis intensity transmittance
    double extinction_ratio = 400.0;       ///< τ/τ_min (the paper's grid, §3.1)
    double angle_offset_deg = 0.0;         ///< δ, mount misalignment added to every angle
    double reflectance = 0.0;              ///< ρ toward the camera
    double reflected_radiance = 0.0;       ///< L_r, band radiance the grid reflects in, W/(m²·sr)
    double reflection_polarization = 0.0;  ///< p in ρ·L_r·(1 + p·cos 2α)
    double emissivity = 0.0;               ///< ε
    double emitted_radiance = 0.0;  ///< L_grid, blackbody band radiance at the grid temperature
};

/// The polarizer evaluated at one angle: the top row of its Mueller matrix and the background B(α).
struct AnalyzerAtAngle {
    Eigen::RowVector4d row;
    double background = 0.0;  ///< B(α), W/(m²·sr)

    /// L(α) = v · row · S + B(α) for a scene Stokes vector (camera frame) and transmission factor
    /// v.
    double radiance(const StokesVector& scene, double transmission_factor = 1.0) const {
        return transmission_factor * row.dot(scene) + background;
    }
};

/// The polarizer at `angle_deg` (nominal; the offset is added). Throws tirpol::Error for an
/// extinction ratio below 1.
AnalyzerAtAngle analyzer_at(const WireGridPolarizer& grid, double angle_deg);

/// C = o + g · L + σ · u (see the file comment).
inline double detector_counts(double radiance, double gain, double offset, double noise_sigma,
                              double unit_normal) {
    return offset + gain * radiance + noise_sigma * unit_normal;
}

}  // namespace tirpol
