#pragma once
/// \file session_calibration.h
/// The thin layer between capture sessions (core/session.h, docs/session-format.md) and the image
/// algorithms of this module: which records feed which step, units, saturation and uncertainties.
///
/// Conventions on top of session schema v1/v2 (docs/calibration.md, "Sessions"):
/// - Angles: from schema v2 the polarizer angle of a record is its read-back `angle_deg_measured`
///   (v1: `angle_deg_requested`); a v2 record whose read-backs are further from the request than
///   the plan's `angle_tolerance_deg` is refused, naming the file. The ideal analyzer of
///   reduce_session sits at the mean measured angle of each requested angle's repeats.
/// - `metadata.polarizer_in_beam` (bool, default false) says whether the blackbody records were
///   taken through the polarizer. Radiometric calibration refuses a session where it is true;
///   polarimetric calibration refuses one where it is false or absent.
/// - `metadata.known_source` (optional) describes the known polarized source seen in the polarizer
///   records of one `repeat`: a list of {repeat, stokes: [S0, S1, S2]} or {repeat,
///   blackbody_temperature_k, reference_polarizer_deg} (an ideal reference polarizer in front of a
///   blackbody: S = ½·L(T)·(1, cos 2θ, sin 2θ)). Those repeats calibrate the analyzer; the other
///   polarizer records are the scene.
/// - Saturation: counts ≥ 2^bits_per_pixel − 1 (bits 1–23; none for float cameras).

#include <atomic>
#include <filesystem>
#include <optional>

#include "tirpol/calibration/analyzer.h"
#include "tirpol/calibration/polarimetric_file.h"
#include "tirpol/calibration/radiometric.h"
#include "tirpol/calibration/stokes_reduction.h"
#include "tirpol/core/session.h"

namespace tirpol::calibration {

/// Saturation level of the session's camera, if it has one.
std::optional<double> session_saturation_counts(const SessionManifest& manifest);

/// Radiometric calibration from the session's blackbody records (and shutter records with a
/// temperature). Throws tirpol::Error for a corrupt manifest, missing frames or the errors of
/// fit_radiometric; camera_id is "vendor model serial (uri)".
RadiometricCalibration calibrate_radiometric_session(const std::filesystem::path& dir,
                                                     const Band& band,
                                                     RadiometricOptions options = {});

/// The same from several sessions of one camera (e.g. taken at several camera temperatures for an
/// FPA-dependent model, options.fpa_degree ≥ 1; each record's fpa_temperature_k is used). Refuses
/// sessions of different cameras. With `quality`, also residuals per set-point, NEDT and warnings
/// (assess_calibration; its warnings are appended to the calibration's).
RadiometricCalibration calibrate_radiometric_sessions(
    const std::vector<std::filesystem::path>& dirs, const Band& band,
    RadiometricOptions options = {}, CalibrationQuality* quality = nullptr);

/// Polarimetric calibration: τ/B maps from the blackbody records through the polarizer (radiance
/// via `radiometric`), the analyzer by least squares from the known-source repeats; when there are
/// none, from `datasheet` if given, else ideal — analyzer_method says which (and that datasheet
/// values were not used when known-source records took precedence).
PolarimetricCalibration calibrate_polarimetric_session(
    const std::filesystem::path& dir, const RadiometricCalibration& radiometric,
    const std::optional<DatasheetAnalyzer>& datasheet = std::nullopt);

struct SessionReductionOptions {
    /// Update the offset from the session's shutter record with a temperature first (or, when the
    /// polarizer was out of the beam, a blackbody record).
    bool update_offset = false;
    /// Correct each scene record for the offset drift during the session (offset_drift.h): from the
    /// plan's in-scene reference region, else interpolated in time between temperature-tagged
    /// shutter records.
    bool drift_correction = false;
    /// Saturated scene pixels become NaN; more than this fraction of any image is an error.
    double max_saturated_fraction = 0.01;
    /// Add the L_SLAR_<angle> channels (ReductionOptions::include_slar).
    bool include_slar = false;
    /// Apply the calibration even if it was made with another camera (serial, model, bit depth or
    /// pixel format differ); without it that is an error naming both cameras.
    bool force_other_camera = false;
    /// Checked before each record is read and during the reduction (ReductionOptions::cancel): once
    /// set, reduce_session throws tirpol::Cancelled. Null: never.
    const std::atomic<bool>* cancel = nullptr;
};

/// Throws tirpol::Error naming both cameras unless `calibration` was made with the session's camera
/// (same size, and serial, model, bit depth and pixel format where the calibration records them).
void check_same_camera(const RadiometricCalibration& calibration, const SessionManifest& session,
                       const std::filesystem::path& dir);

/// Reduces the session's scene records to Stokes (S0 S1 S2 DoLP AoP + *_std), radiance units.
/// Records at the same angle (repeats) are averaged. Bad pixels of `radiometric` are replaced. Each
/// record is converted at its own fpa_temperature_k; records whose apparent radiance or FPA
/// temperature lie outside the calibrated range are listed (one line each, extrapolation_warning)
/// in the attribute `calibration_warnings`. With options.update_offset, the correction and its
/// uncertainty are attributes: offset_update_source, offset_update_mean_counts (mean change of the
/// offset over good pixels), offset_update_sigma_counts and offset_update_sigma_mk (median
/// per-pixel σ of the reference frame's mean, the uncertainty the update adds to every pixel). With
/// options.drift_correction: drift_correction_source, and per scene record (in record order, files
/// in drift_records, one per line) drift_offset_counts, drift_offset_sigma_counts and drift_time_s
/// (seconds since the first scene record).
Image reduce_session(const std::filesystem::path& dir, const RadiometricCalibration& radiometric,
                     const PolarimetricCalibration* polarimetric,
                     const SessionReductionOptions& options = {});

}  // namespace tirpol::calibration
