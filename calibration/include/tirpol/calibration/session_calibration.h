#pragma once
/// \file session_calibration.h
/// The thin layer between capture sessions (core/session.h, docs/session-format.md) and the image
/// algorithms of this module: which records feed which step, units, saturation and uncertainties.
///
/// Conventions on top of session schema v1 (docs/calibration.md, "Sessions"):
/// - `metadata.polarizer_in_beam` (bool, default false) says whether the blackbody records were
///   taken through the polarizer. Radiometric calibration refuses a session where it is true;
///   polarimetric calibration refuses one where it is false or absent.
/// - `metadata.known_source` (optional) describes the known polarized source seen in the polarizer
///   records of one `repeat`: a list of {repeat, stokes: [S0, S1, S2]} or {repeat,
///   blackbody_temperature_k, reference_polarizer_deg} (an ideal reference polarizer in front of a
///   blackbody: S = ½·L(T)·(1, cos 2θ, sin 2θ)). Those repeats calibrate the analyzer; the other
///   polarizer records are the scene.
/// - Saturation: counts ≥ 2^bits_per_pixel − 1 (bits 1–23; none for float cameras).

#include <filesystem>
#include <optional>

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
RadiometricCalibration calibrate_radiometric_session(const std::filesystem::path& dir, const Band& band,
                                                     RadiometricOptions options = {});

/// Polarimetric calibration: τ/B maps from the blackbody records through the polarizer (radiance via
/// `radiometric`), the analyzer by least squares from the known-source repeats (ideal at the
/// blackbody angles when there are none).
PolarimetricCalibration calibrate_polarimetric_session(const std::filesystem::path& dir,
                                                       const RadiometricCalibration& radiometric);

struct SessionReductionOptions {
    /// Update the offset from the session's shutter record with a temperature first (or, when the
    /// polarizer was out of the beam, a blackbody record).
    bool update_offset = false;
    /// Saturated scene pixels become NaN; more than this fraction of any image is an error.
    double max_saturated_fraction = 0.01;
    /// Add the L_SLAR_<angle> channels (ReductionOptions::include_slar).
    bool include_slar = false;
    /// Apply the calibration even if it was made with another camera (serial, model, bit depth or
    /// pixel format differ); without it that is an error naming both cameras.
    bool force_other_camera = false;
};

/// Throws tirpol::Error naming both cameras unless `calibration` was made with the session's camera
/// (same size, and serial, model, bit depth and pixel format where the calibration records them).
void check_same_camera(const RadiometricCalibration& calibration, const SessionManifest& session,
                       const std::filesystem::path& dir);

/// Reduces the session's scene records to Stokes (S0 S1 S2 DoLP AoP + *_std), radiance units.
/// Records at the same angle (repeats) are averaged. Bad pixels of `radiometric` are replaced.
Image reduce_session(const std::filesystem::path& dir, const RadiometricCalibration& radiometric,
                     const PolarimetricCalibration* polarimetric, const SessionReductionOptions& options = {});

}  // namespace tirpol::calibration
