#pragma once
/// \file polarimetric_file.h
/// The polarimetric calibration: a YAML file a person can read (analyzer model per angle, where it
/// came from) next to an EXR of the per-pixel wire-grid maps (docs/calibration.md).

#include <string>

#include "tirpol/calibration/analyzer.h"
#include "tirpol/calibration/wire_grid.h"

namespace tirpol::calibration {

struct PolarimetricCalibration {
    AnalyzerModel analyzer;
    /// "known-source least squares" or "ideal (no known-source records)".
    std::string analyzer_method;
    WireGridCalibration wire_grid;
    std::string session;                  ///< the session it was made from
    std::string radiometric_calibration;  ///< the radiometric calibration the signals were in
    std::string created_utc;
};

/// The maps file written next to `yaml_path`: same stem, extension ".maps.exr".
std::string polarimetric_maps_path(const std::string& yaml_path);

/// Writes POL.yaml and POL.maps.exr (channels tau_<angle>, B_<angle>, residual_<angle>, the angle
/// written with 'p' for the decimal point, e.g. tau_22p5). Both atomic.
void write_polarimetric_calibration(const std::string& yaml_path, const PolarimetricCalibration& cal);

/// Reads both files; errors name the file and the field or channel.
PolarimetricCalibration read_polarimetric_calibration(const std::string& yaml_path);

}  // namespace tirpol::calibration
