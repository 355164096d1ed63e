#pragma once
/// \file polarimetric_file.h
/// The polarimetric calibration: a YAML file a person can read (analyzer model per angle, where it
/// came from) next to an EXR of the per-pixel wire-grid maps (docs/calibration.md).

#include <string>

#include "tirpol/calibration/analyzer.h"
#include "tirpol/calibration/radiometric.h"
#include "tirpol/calibration/stokes_reduction.h"

namespace tirpol::calibration {

struct PolarimetricCalibration {
    AnalyzerModel analyzer;
    /// "known-source least squares" or "ideal (no known-source records)".
    std::string analyzer_method;
    WireGridCalibration wire_grid;
    std::string session;                  ///< the session it was made from
    std::string radiometric_calibration;  ///< the radiometric calibration the signals were in
    std::string created_utc;
    /// The band of that radiometric calibration, µm (τ and B hold only in it); 0, 0 in files
    /// written before tirpol recorded it (`band_um` in the YAML).
    double band_lo_um = 0.0, band_hi_um = 0.0;
    bool band_known() const { return band_hi_um > 0.0; }
};

/// Throws tirpol::Error naming both calibrations (`radiometric_name`, `polarimetric_name`) and
/// their bands unless the polarimetric calibration was made in the radiometric calibration's band
/// (edges within 1e-6 µm; a polarimetric file without a band is not checked). τ and B maps fitted
/// in one band, applied to radiances of another, give nonsense (negative S0, DoLP NaN).
void check_same_band(const RadiometricCalibration& radiometric, const std::string& radiometric_name,
                     const PolarimetricCalibration& polarimetric,
                     const std::string& polarimetric_name);

/// The maps file written next to `yaml_path`: same stem, extension ".maps.exr".
std::string polarimetric_maps_path(const std::string& yaml_path);

/// Writes POL.yaml and POL.maps.exr (channels tau_<angle>, B_<angle>, residual_<angle>, the angle
/// written with 'p' for the decimal point, e.g. tau_22p5). Both atomic.
void write_polarimetric_calibration(const std::string& yaml_path,
                                    const PolarimetricCalibration& cal);

/// Reads both files; errors name the file and the field or channel.
PolarimetricCalibration read_polarimetric_calibration(const std::string& yaml_path);

}  // namespace tirpol::calibration
