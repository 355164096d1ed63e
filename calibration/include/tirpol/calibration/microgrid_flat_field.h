#pragma once
/// \file microgrid_flat_field.h
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

#include <cstddef>
#include <filesystem>
#include <vector>

#include "tirpol/calibration/bad_pixels.h"
#include "tirpol/calibration/microgrid_pixel_calibration.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::calibration {

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
