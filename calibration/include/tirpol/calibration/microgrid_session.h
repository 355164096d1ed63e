#pragma once
/// \file microgrid_session.h
/// A capture session of a microgrid (division-of-focal-plane) camera → Stokes image. The session's
/// manifest records the camera's 2×2 analyzer pattern (`camera.microgrid_pattern_deg`, session
/// schema v5); every polarizer record holds whole mosaics, so the records are averaged (weighted by
/// their frame counts) and the mean mosaic is reduced: demosaiced and reduced with ideal analyzers
/// at the pattern's angles (reduce_microgrid), or, with a per-pixel calibration, per 2×2
/// super-pixel with each pixel's own analysis vector (reduce_microgrid_per_pixel).
///
/// Per-pixel analyzer calibration of a microgrid camera and the reduction that uses it, after
/// S. B. Powell & V. Gruev, "Calibration methods for division-of-focal-plane polarimeters",
/// Opt. Express 21(18), 21039 (2013): the micro-polarizers' axis, diattenuation and transmission
/// vary across the array (by up to 20 %), so every pixel gets its own analysis vector, fitted from
/// frames of a uniform source of known Stokes (a blackbody seen through a reference polarizer at
/// known angles, and at two radiances), and each 2×2 super-pixel is reduced by its own 3×4
/// data-reduction matrix.
///
/// Pixel model (the row of analyzer.h, per pixel i): I_i = w_i·S + b_i with w_i = ½·t_i·(1, d_i cos
/// 2θ_i, d_i sin 2θ_i), S = (S0, S1, S2) in the camera frame of ARCHITECTURE.md, b_i an additive
/// background.
///
/// A microgrid camera's per-pixel calibration from flat-field capture sessions (the rig tirpol
/// drives: a blackbody filling the view, a reference wire-grid polarizer on the rotation stage):
/// the two-point non-uniformity correction (NUC) from the open blackbody at ≥ 2 temperatures, each
/// pixel's analyzer (axis, diattenuation) from the blackbody seen through the reference polarizer
/// at ≥ 3 angles and ≥ 2 temperatures (S. B. Powell & V. Gruev, Opt. Express 21(18), 21039, 2013,
/// with a background term per pixel), and bad pixels. The result is a MicrogridPixelCalibration in
/// band radiance, which reduce_microgrid_session applies per super-pixel.
///
/// Per pixel i, counts = w_i·S + b_i with w_i = g_i·(1, d_i cos 2θ_i, d_i sin 2θ_i), S the band
/// radiance Stokes vector (W/(m² sr), camera frame of ARCHITECTURE.md):
/// - open blackbody at T: S = (L(T), 0, 0), so counts = g_i·L(T) + b_i: the NUC's gain g_i (the
///   micro-polarizer's transmission times the bolometer's responsivity) and offset b_i;
/// - through the reference polarizer at φ: counts = a_i·L + L·(m_i1 cos 2φ + m_i2 sin 2φ) + b'_i.
///   Only the ratio (m_i1, m_i2)/a_i = d_i (cos 2θ_i, sin 2θ_i) is used, so the reference
///   polarizer's transmission and its unpolarized emission and reflection (absorbed in b'_i, which
///   is fitted separately from b_i) do not bias the analyzer.
///
/// Session conventions (docs/microgrid.md, "Calibrating a microgrid camera"): the manifest records
/// the camera's pattern; `blackbody` records are the open blackbody (`metadata.polarizer_in_beam`
/// absent or false); `polarizer` records are the blackbody through the reference polarizer, whose
/// axis is the record's polarizer angle (record_polarizer_angle_deg) plus
/// `metadata.microgrid_flat_field.reference_polarizer_axis_offset_deg`, and whose blackbody
/// temperature is given per repeat in `metadata.microgrid_flat_field.polarizer_repeats`
/// (a list of {repeat, blackbody_temperature_k}). The reference polarizer's diattenuation is
/// `reference_polarizer_diattenuation` (optional, 1 = ideal when absent).

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "tirpol/calibration/microgrid_session.h"
#include "tirpol/calibration/microgrid_stokes.h"
#include "tirpol/calibration/radiometric.h"
#include "tirpol/core/image.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::calibration {

/// One calibration frame: a uniform source of known Stokes vector (S0, S1, S2) filling the view,
/// and the (frame-averaged) microgrid frame, row-major.
struct MicrogridFlatField {
    Eigen::Vector3d source_stokes;
    std::vector<float> frame;
};

/// Each pixel's analysis vector w_i and background b_i (planes, row-major).
struct MicrogridPixelCalibration {
    int width = 0;
    int height = 0;
    std::array<std::vector<float>, 3> analysis;  ///< w_i0, w_i1, w_i2
    std::vector<float> background;               ///< b_i (0 when not fitted)
    /// BadPixel bit mask (bad_pixels.h) as float, 0 = good; empty when no pixel was assessed.
    /// Reduction leaves a bad pixel out of its super-pixel.
    std::vector<float> bad;
    double fit_rms = 0.0;  ///< RMS residual of the per-pixel fits, signal units
    /// Per pixel, the standard deviation of its fit's residuals, √(RSS_i/(J − p)) for J flat fields
    /// and p = 4 parameters (3 without background); empty when not known (no more sources than
    /// parameters, or a calibration made another way).
    std::vector<float> residual_std;
    /// (AᵀA)⁻¹ of the fits' design matrix A (rows (S_j, 1)), p×p row-major: pixel i's parameters
    /// (w_i0, w_i1, w_i2[, b_i]) have the covariance residual_std[i]² · this (least squares with
    /// independent errors of equal variance per pixel). Empty with residual_std.
    std::vector<double> unit_parameter_covariance;
    /// Per pixel, the covariance of its parameters (w_i0, w_i1, w_i2, b_i) where it differs from
    /// pixel to pixel in more than a scale (a calibration from flat-field sessions, propagated
    /// from the records' temporal noise): the upper triangle's 10 entries in the order 00 01 02
    /// 03 11 12 13 22 23 33, each a plane (signal units², the w in signal per Stokes unit); empty
    /// when not known. Reduction uses it in place of residual_std and unit_parameter_covariance.
    std::array<std::vector<float>, 10> parameter_covariance;
    /// Units of the Stokes vectors the analysis vectors map from (e.g. "W/(m^2 sr)" when the
    /// sources were blackbody band radiances); empty when not known. Reduction writes it as
    /// `units`.
    std::string stokes_units;

    /// t_i = 2·w_i0 (1 for an ideal polarizer).
    float transmission(std::size_t i) const { return 2.0f * analysis[0][i]; }
    /// d_i = |(w_i1, w_i2)|/w_i0.
    float diattenuation(std::size_t i) const;
    /// θ_i = ½·atan2(w_i2, w_i1) in degrees, [0, 180).
    float axis_angle_deg(std::size_t i) const;
    /// Whether pixel i is marked bad.
    bool is_bad(std::size_t i) const { return !bad.empty() && bad[i] != 0.0f; }
    /// Whether the fit's uncertainties are known (residual_std and unit_parameter_covariance, or
    /// parameter_covariance).
    bool has_uncertainties() const { return !residual_std.empty() || has_pixel_covariance(); }
    /// Whether each pixel's parameter covariance is given (parameter_covariance).
    bool has_pixel_covariance() const { return !parameter_covariance[0].empty(); }
    /// Channels `transmission`, `diattenuation`, `axis_angle_deg`, `background`, `w0`, `w1`, `w2`
    /// and, when assessed, `bad`; with uncertainties the parameters' standard uncertainties
    /// `w0_std`, `w1_std`, `w2_std` (and `background_std` when fitted) and either `residual_std`
    /// with the attribute `unit_parameter_covariance`, or the per-pixel covariance as channels
    /// `cov_w0_w0`, `cov_w0_w1`, … `cov_b_b` (parameter_covariance's order); attributes `fit_rms`
    /// and, when known, `stokes_units`: the calibration as an EXR-ready image (the w, background,
    /// bad, residual_std planes and the covariance are what reduction reads).
    Image to_image() const;
    /// The inverse of to_image(); throws tirpol::Error naming a missing channel. A file without a
    /// `bad` channel (written before bad pixels were assessed) reads with no pixel marked bad.
    static MicrogridPixelCalibration from_image(const Image& image);
};

/// Fits every pixel by linear least squares over the flat fields: I_ij = w_i·S_j + b_i (with
/// `fit_background`, else b_i = 0). The design matrix is the same for every pixel, so its
/// pseudo-inverse is computed once. Throws tirpol::Error for frames of the wrong size, non-finite
/// values, or sources that do not determine the model: fewer than 4 (3 without background), or not
/// spanning (S0, S1, S2[, 1]), e.g. a reference polarizer at one radiance only with a background.
MicrogridPixelCalibration calibrate_microgrid_pixels(
    const std::vector<MicrogridFlatField>& flat_fields, int width, int height,
    bool fit_background = true);

/// Reduces a microgrid frame with the per-pixel calibration, one Stokes vector per 2×2 super-pixel:
/// S = (WᵀW)⁻¹Wᵀ(I − b) with W the 4×3 matrix of the cell's analysis vectors (the pattern is
/// implicit in them). A pixel marked bad is left out (its row dropped): three good analyzers at
/// distinct angles still determine S; such cells are counted in `cells_with_bad_pixels`. Output:
/// half-size image with S0 S1 S2 DoLP AoP (deg, [0, 180)), attributes `demosaic_method` =
/// "super-pixel", `analyzer_model` = "per-pixel", `units` when the calibration knows them. Throws
/// tirpol::Error for a frame of another size than the calibration's or a non-finite value at a good
/// pixel; a cell whose good rows do not determine S (fewer than 3, or a dead analyzer) gives NaN
/// for that super-pixel and is counted in the attribute `singular_cells`.
Image reduce_microgrid_per_pixel(std::span<const float> mosaic,
                                 const MicrogridPixelCalibration& calibration);

/// reduce_microgrid_per_pixel with its per-super-pixel work done once: each cell's 3×4 matrix
/// M = (WᵀW)⁻¹Wᵀ (a bad pixel's column zero) and offset −M·b, so that reducing a frame is one
/// matrix-vector product per cell (for a live view or many frames of one camera). Equal to
/// reduce_microgrid_per_pixel to float rounding (it is what that function runs).
class MicrogridPixelReducer {
public:
    /// Throws tirpol::Error for a calibration whose planes do not hold width × height values.
    explicit MicrogridPixelReducer(const MicrogridPixelCalibration& calibration);
    /// The output of reduce_microgrid_per_pixel for `mosaic` (same checks and attributes). When the
    /// calibration has uncertainties or `mosaic_std` (each pixel's σ, e.g. of a frame mean) is
    /// given, also S0_std S1_std S2_std DoLP_std AoP_std, to first order as reduce_stokes does: per
    /// pixel k of a cell, var_k = σ_k² + (S, 1)ᵀ·Cov(w_k, b_k)·(S, 1) (the error of I_k − b_k −
    /// w_k·S at the cell's S), Cov(S) = Σ_k var_k·m_k·m_kᵀ with m_k column k of M; attribute
    /// `std_includes` says which. Throws tirpol::Error for a σ plane of the wrong size or holding a
    /// negative or non-finite value at a good pixel.
    Image reduce(std::span<const float> mosaic, std::span<const float> mosaic_std = {}) const;

    int width() const { return m_width; }
    int height() const { return m_height; }

private:
    /// The σ channels of `out` (S0 S1 S2 present) from the frame's σ and the calibration's.
    void add_uncertainties(Image& out, std::span<const float> mosaic_std) const;

    int m_width = 0, m_height = 0;
    /// Per cell, row-major over the half-size image: M's 12 entries (row r, pixel k at 4r + k,
    /// k = 2·(y mod 2) + (x mod 2)) and the 3 offsets; NaN for a singular cell.
    std::array<std::vector<float>, 12> m_matrix;
    std::array<std::vector<float>, 3> m_offset;
    std::vector<unsigned char> m_bad;   ///< per pixel; its value is never read
    std::vector<float> m_residual_var;  ///< per pixel, residual_std²; empty without uncertainties
    std::vector<double> m_unit_covariance;                  ///< p×p, see unit_parameter_covariance
    std::array<std::vector<float>, 10> m_pixel_covariance;  ///< see parameter_covariance
    int m_parameters = 0;                                   ///< p: 4 with background, 3 without
    int m_singular_cells = 0, m_cells_with_bad_pixels = 0;
    std::string m_units;
};

struct MicrogridSessionOptions {
    DemosaicMethod method = DemosaicMethod::Newton;  ///< without a per-pixel calibration
    /// Each pixel's analysis vector (Powell & Gruev); its size must be the camera's. When set, the
    /// output is per super-pixel (half size) and `method` is not used.
    std::optional<MicrogridPixelCalibration> pixel_calibration;
};

/// True when the session at `dir` was recorded by a microgrid camera (its manifest records a
/// pattern). Throws tirpol::Error as read_session does for a damaged session.
bool is_microgrid_session(const std::filesystem::path& dir);

/// Reduces the session at `dir`. Output channels S0 S1 S2 DoLP AoP in counts (with a per-pixel
/// calibration: in its Stokes units, and S0_std … AoP_std from the records' temporal σ and the
/// calibration's parameter uncertainties, MicrogridPixelReducer::reduce), attributes those of
/// the reduction plus `session` (the directory), `records_averaged`, `frames_averaged` and the
/// pattern. Throws tirpol::Error naming the session when it records no microgrid pattern (a
/// rotating-polarizer session), has no polarizer record, or its pattern does not determine S1 and
/// S2; naming the calibration when its size is not the camera's.
Image reduce_microgrid_session(const std::filesystem::path& dir,
                               const MicrogridSessionOptions& options = {});

/// What reduce_microgrid_session records about a reduction, read back from its image.
struct MicrogridSessionRecord {
    MicrogridPattern pattern;  ///< the session camera's
    int records_averaged{};    ///< polarizer records
    int frames_averaged{};     ///< camera frames over those records
    /// Units of S0, S1, S2: "counts", or the per-pixel calibration's Stokes units; empty when the
    /// calibration does not state them.
    std::string units;
};

/// The record of the session reduction that made `stokes`. Throws tirpol::Error naming the
/// attribute when one is missing or of the wrong type (an image not made by
/// reduce_microgrid_session).
MicrogridSessionRecord microgrid_session_record(const Image& stokes);

struct MicrogridFlatFieldOptions {
    BadPixelThresholds thresholds;  ///< dead, hot, noisy and non-linear pixels
    /// A pixel whose fitted diattenuation is below this (or above 1 + its 5 % tolerance) is
    /// kBadAnalyzer.
    double min_diattenuation = 0.5;
    /// ... and so is one whose axis is further than this from the pattern's nominal angle, degrees.
    double max_axis_error_deg = 10.0;
};

/// What calibrate_microgrid_sessions made and what it saw.
struct MicrogridFlatFieldCalibration {
    /// Analysis vectors in counts per W/(m² sr), backgrounds in counts, bad pixels;
    /// stokes_units = "W/(m^2 sr)". fit_rms: RMS residual of the polarizer-record fits, counts.
    MicrogridPixelCalibration pixels;
    /// The same NUC (gain, offset, bad pixels) with ideal analyzers at the pattern's nominal
    /// angles (d = 1): what a two-point NUC alone gives, for comparison.
    MicrogridPixelCalibration nuc_only;
    std::size_t open_blackbody_records = 0;
    std::size_t polarizer_records = 0;
    double nuc_fit_rms_counts = 0.0;  ///< RMS residual of the two-point NUC fits
    /// Over good pixels: relative spread (robust σ / median) of the gain g_i, and the analyzer
    /// diattenuation (median, robust σ) and axis error from the nominal angle (RMS, degrees).
    double gain_rel_spread = 0.0;
    double diattenuation_median = 0.0;
    double diattenuation_spread = 0.0;
    double axis_error_rms_deg = 0.0;
    std::size_t bad_count(std::uint32_t bits = 0xffffffffu) const;
};

/// Calibrates the microgrid camera from the flat-field sessions `dirs` (one or more, of the same
/// camera: size, serial and pattern), band radiances over `band`. Throws tirpol::Error naming the
/// session and field for: a session without a microgrid pattern, cameras that differ, open
/// blackbody records at fewer than 2 temperatures, polarizer records whose repeat has no
/// blackbody temperature, polarizer records at fewer than 3 angles or 2 temperatures, blackbody
/// records taken through the polarizer, unreadable frames.
MicrogridFlatFieldCalibration calibrate_microgrid_sessions(
    const std::vector<std::filesystem::path>& dirs, const Band& band,
    const MicrogridFlatFieldOptions& options = {});

}  // namespace tirpol::calibration
