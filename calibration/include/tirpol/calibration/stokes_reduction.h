#pragma once
/// \file stokes_reduction.h
/// Stokes reduction S = W⁺·L_SLAR per pixel with propagated uncertainties, in the Stokes convention
/// of ARCHITECTURE.md (S1 = I0 − I90, S2 = I45 − I135, 0° along image rows, 90° to the top).
///
/// What the tilted wire grid adds in front of an uncooled camera (paper §3.1; J. A. Shaw & M. R.
/// Descour, "Instrument effects in polarized infrared images", Opt. Eng. 34, 1995): a structured
/// ghost of the camera interior, the sky it is tilted to reflect, and its own emission. Per pixel
/// and analyzer position α: I(α) = τ(α)·L_scene(α) + B(α), where L_scene(α) = a(α)·S is the
/// radiance the normalised analyzer row passes (½·L for an unpolarized source, analyzer.h) and I(α)
/// is the apparent radiance of the radiometrically calibrated camera (or counts). τ and B are
/// fitted per pixel from blackbody frames at ≥ 2 temperatures through the polarizer at every
/// position. The surface-leaving, aperture-reaching radiance of eq 17 is then L_SLAR(α) = (I(α) −
/// B(α))/τ(α).

#include <atomic>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "tirpol/calibration/analyzer.h"
#include "tirpol/core/image.h"
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

/// The measurement at one analyzer position: `signal` (radiance or counts) and its per-pixel
/// standard uncertainty `signal_std` (σ of the frame mean, may be empty = unknown).
struct AnalyzerImage {
    double angle_deg = 0.0;
    std::vector<float> signal;
    std::vector<float> signal_std;
    std::string source;
};

/// The same measurement as a view of planes owned elsewhere (numpy arrays, a mapped file): what
/// reduce_stokes reads, so such callers reduce without copying their pixels.
struct AnalyzerPlanes {
    double angle_deg = 0.0;
    std::span<const float> signal;
    std::span<const float> signal_std;  ///< empty = unknown
    std::string source;
};

struct ReductionOptions {
    /// Pixels whose Stokes vector is not realizable (√(S1²+S2²) > S0, noise) get (S1, S2) scaled
    /// onto the cone S0 = √(S1²+S2²); their count is reported. Off: leave them as measured.
    bool project_to_realizable = true;
    /// Also output the wire-grid-corrected radiance per angle, L_SLAR(α) = (I − B)/τ, as channels
    /// `L_SLAR_<angle>` (angle with 'p' for a decimal point, e.g. L_SLAR_22p5).
    bool include_slar = false;
    std::string units = "W/(m^2 sr)";
    /// Checked at the start of every image row: once set, reduce_stokes throws tirpol::Cancelled
    /// (how the Python module stops a reduction on Ctrl-C). Null: never.
    const std::atomic<bool>* cancel = nullptr;
};

/// Reduces N ≥ 3 analyzer images to an Image with channels S0 S1 S2 DoLP AoP and, when every input
/// has `signal_std`, S0_std S1_std S2_std DoLP_std AoP_std (first-order propagation of the
/// independent per-angle σ through W⁺, and of the Stokes covariance to DoLP and AoP; AoP_std is
/// capped at 180°/√12 ≈ 52°, the σ of an AoP uniform on [0°, 180°), where DoLP ≈ noise). With
/// `wire_grid`, inputs are first corrected: L_SLAR = (I − B)/τ. Throws tirpol::Error (before any
/// output) for: an angle of the model with no image, sizes that differ, NaN/inf inputs.
/// Attributes: units, units_DoLP, units_AoP, analyzer_angles_deg, drm (row-major 3×N),
/// unrealizable_pixels.
Image reduce_stokes(const std::vector<AnalyzerImage>& images, int width, int height,
                    const AnalyzerModel& model, const WireGridCalibration* wire_grid = nullptr,
                    const ReductionOptions& options = {});
/// The same on views; the planes must outlive the call.
Image reduce_stokes(const std::vector<AnalyzerPlanes>& images, int width, int height,
                    const AnalyzerModel& model, const WireGridCalibration* wire_grid = nullptr,
                    const ReductionOptions& options = {});

/// Header attributes of a reduced Stokes image that say how the reduction went; their names are
/// the Stokes EXR's, written only here (reduce_stokes and the microgrid reductions).
inline constexpr const char* kUnrealizablePixelsAttribute = "unrealizable_pixels";
inline constexpr const char* kWireGridCorrectedAttribute = "wire_grid_corrected";

/// What a Stokes reduction records about itself, read back from its image.
struct StokesReductionRecord {
    /// Pixels whose measured vector was not realizable (√(S1²+S2²) > S0), projected onto the cone
    /// when ReductionOptions::project_to_realizable.
    int unrealizable_pixels = 0;
    /// Inputs were corrected by a wire-grid calibration; empty when the image does not say (a
    /// Stokes EXR written before the reductions recorded it).
    std::optional<bool> wire_grid_corrected;
};

/// The record of the reduction that made `stokes`. Throws tirpol::Error naming the attribute when
/// `unrealizable_pixels` is missing, or either attribute is there but not an integer (an image not
/// written by a Stokes reduction).
StokesReductionRecord stokes_reduction_record(const Image& stokes);

}  // namespace tirpol::calibration
