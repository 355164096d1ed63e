#pragma once
/// \file wire_grid.h
/// What the tilted wire grid adds in front of an uncooled camera (paper §3.1; J. A. Shaw & M. R.
/// Descour, "Instrument effects in polarized infrared images", Opt. Eng. 34, 1995): a structured
/// ghost of the camera interior, the sky it is tilted to reflect, and its own emission. Per pixel
/// and analyzer position α: I(α) = τ(α)·L_scene(α) + B(α), where L_scene(α) = a(α)·S is the
/// radiance the normalised analyzer row passes (½·L for an unpolarized source, analyzer.h) and I(α)
/// is the apparent radiance of the radiometrically calibrated camera (or counts). τ and B are
/// fitted per pixel from blackbody frames at ≥ 2 temperatures through the polarizer at every
/// position. The surface-leaving, aperture-reaching radiance of eq 17 is then L_SLAR(α) = (I(α) −
/// B(α))/τ(α).

#include <string>
#include <vector>

#include "tirpol/calibration/analyzer.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::calibration {

/// A blackbody frame through the polarizer: `signal` is the measurement I (radiance or counts),
/// `signal_std` the per-pixel σ of that (frame-mean) signal, or empty when unknown.
struct PolarizedBlackbodyFrame {
    double angle_deg = 0.0;
    double temperature_k = 0.0;
    std::vector<float> signal;
    std::string source;
    std::vector<float> signal_std;
};

/// Per-pixel τ and B maps of one analyzer position.
struct WireGridPosition {
    double angle_deg = 0.0;
    std::vector<float> tau;         ///< dimensionless
    std::vector<float> background;  ///< units of the signal
    std::vector<float> residual_rms;
    /// Per-pixel covariance of the fitted (τ, B) from the frames' σ: Var τ, Var B, Cov(τ, B). The
    /// fit's error is fixed for the session (the same at every frame), so it adds to the temporal
    /// noise of a reduced image instead of averaging away. Empty when the frames carried no σ.
    std::vector<float> tau_var, background_var, tau_background_cov;

    /// True when the (τ, B) covariance maps are present.
    bool has_covariance() const { return !tau_var.empty(); }
};

struct WireGridCalibration {
    int width = 0, height = 0;
    std::vector<WireGridPosition> positions;
    /// The position with nominal angle `angle_deg` (±0.01°); throws tirpol::Error naming the
    /// angles present otherwise.
    const WireGridPosition& at(double angle_deg) const;
};

/// Fits τ(α), B(α) per pixel: signal = τ·½·L_band(T) + B over the frames of each angle, by least
/// squares; when every frame has `signal_std`, also their covariance (P·diag(σ²)·Pᵀ, P the
/// least-squares projector, exact for independent frame errors). Throws
/// tirpol::Error for an angle with fewer than 2 distinct temperatures, mismatched sizes or NaNs.
WireGridCalibration fit_wire_grid(const std::vector<PolarizedBlackbodyFrame>& frames, int width,
                                  int height, const Band& band);

/// The wire grid's additive term from a measured sky radiance instead of blackbody frames:
/// B = r·L_sky + ε_grid·L_band(T_grid), uniform over the image, in radiance units (the grid's
/// reflectance r toward the sky and its emissivity ε_grid = 1 − τ_unpolarized − r).
double wire_grid_background(double grid_reflectance, double sky_radiance_w_m2_sr,
                            double grid_emissivity, double grid_temperature_k, const Band& band);

}  // namespace tirpol::calibration
