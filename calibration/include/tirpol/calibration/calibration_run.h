#pragma once
/// \file calibration_run.h
/// `tirpol calibrate radiometric` and `tirpol calibrate polarimetric` from sessions to files: the
/// chain step (run_calibration_chain), the files it writes, and the text summary of each.

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/calibration/calibration_quality.h"
#include "tirpol/calibration/polarimetric_file.h"
#include "tirpol/calibration/radiometric.h"

namespace tirpol::calibration {

/// Blackbody sessions, the band (with an RSR file, "" = flat), the model and the files to write.
struct RadiometricRunOptions {
    std::vector<std::string> sessions;
    std::array<double, 2> band_um{8.0, 14.0};
    std::string rsr;
    bool quadratic = false;
    int fpa_degree = 0;
    std::optional<double> saturation_counts;
    std::string output;   ///< calibration EXR
    std::string summary;  ///< quality summary folder (default_summary_dir of output)
};

/// What run_radiometric_calibration fitted and wrote.
struct RadiometricRun {
    RadiometricRunOptions options;
    RadiometricCalibration calibration;
    CalibrationQuality quality;
};

/// Fits the calibration with its quality assessment and writes the EXR and the summary folder.
/// Throws tirpol::Error for sessions, an RSR or a band that do not read or fit.
RadiometricRun run_radiometric_calibration(const RadiometricRunOptions& options);

/// What `tirpol calibrate radiometric` checks before any work: no output (the EXR, the summary
/// folder) may replace an input or, unless `force`, an existing file (OutputGuard).
void check_radiometric_run(const RadiometricRunOptions& options, bool force);

/// The camera, model, median gain and residual, FPA model, residual per set-point, NEDT,
/// warnings, bad-pixel counts and the files written.
std::string radiometric_run_text(const RadiometricRun& run);

/// A polarizer session, the radiometric calibration and, to model the analyzer from its datasheet
/// instead of the wire-grid fit, the extinction ratio (and axis offsets).
struct PolarimetricRunOptions {
    std::string session;
    std::string calibration;
    std::optional<double> extinction_ratio;
    std::vector<double> axis_offsets_deg;
    std::string output;  ///< YAML; the maps beside it (polarimetric_maps_path)
};

/// Calibrates the analyzer and writes the YAML and its maps. Throws tirpol::Error for a session or
/// calibration that does not read or fit.
PolarimetricCalibration run_polarimetric_calibration(const PolarimetricRunOptions& options);

/// What `tirpol calibrate polarimetric` checks before any work: axis offsets need the extinction
/// ratio (tirpol::OptionValueError naming --axis-offset-deg), and no output (the YAML, its maps)
/// may replace an input or, unless `force`, an existing file (OutputGuard).
void check_polarimetric_run(const PolarimetricRunOptions& options, bool force);

/// The method, each analyzer position, the condition number of W and the files written.
std::string polarimetric_calibration_text(const PolarimetricCalibration& calibration,
                                          const PolarimetricRunOptions& options);

}  // namespace tirpol::calibration
