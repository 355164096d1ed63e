#pragma once
/// \file stokes_reduction.h
/// Stokes reduction S = W⁺·L_SLAR per pixel with propagated uncertainties, in the Stokes convention
/// of ARCHITECTURE.md (S1 = I0 − I90, S2 = I45 − I135, 0° along image rows, 90° to the top).

#include <atomic>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "tirpol/calibration/analyzer.h"
#include "tirpol/calibration/wire_grid.h"
#include "tirpol/core/image.h"

namespace tirpol::calibration {

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
