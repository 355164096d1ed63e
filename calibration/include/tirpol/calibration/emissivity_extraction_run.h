#pragma once
/// \file emissivity_extraction_run.h
/// `tirpol extract-emissivity` from files to a CSV: the polarized emissivity of regions of interest
/// (paper eq 17) from a Stokes EXR, or from a session reduced with its calibration first.

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "tirpol/calibration/emissivity_extraction.h"

namespace tirpol::calibration {

/// The input (a Stokes EXR, or a session directory with its calibration), the regions YAML and the
/// CSV to write. band_um, when set, must agree with the band of the input.
struct EmissivityExtractionOptions {
    std::string input;
    std::string rois;
    std::string output;
    std::string calibration;   ///< radiometric calibration EXR (a session input)
    std::string polarimetric;  ///< polarimetric calibration YAML (a session input), or ""
    std::optional<std::pair<double, double>> band_um;
    bool force = false;  ///< an existing output may be replaced (OutputGuard)
};

/// Checks the output against the inputs (OutputGuard: OutputConflict before any work), runs the
/// chain (run_calibration_chain) to the emissivity of each target and writes the CSV
/// (emissivity_csv). A session without a calibration throws OptionValueError for --calibration;
/// a band that disagrees with the calibration's or the EXR's, or an EXR without band_um and no
/// band given, throws tirpol::Error naming both.
std::vector<EmissivityResult> extract_emissivity(const EmissivityExtractionOptions& options);

/// One line per target: name, view angle, ε_S0, ε_S1, ε_S2 with their 2σ.
std::string emissivity_results_text(const std::vector<EmissivityResult>& results);

}  // namespace tirpol::calibration
