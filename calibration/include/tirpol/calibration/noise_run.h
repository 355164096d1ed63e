#pragma once
/// \file noise_run.h
/// `tirpol noise` from files to files: load a frame stack (and a radiometric calibration), analyse
/// it (analyse_noise), write the JSON report and the per-pixel NEDT map, and summarise as text.

#include <optional>
#include <string>

#include "tirpol/calibration/frame_stack_io.h"
#include "tirpol/calibration/noise_report.h"

namespace tirpol::calibration {

/// The stack (a directory, an EXR of frame_* channels, or a raw file with `raw`), the calibration
/// ("" = counts only), the analysis options and the files to write.
struct NoiseRunOptions {
    std::string stack;
    std::optional<RawFrameFormat> raw;
    std::string calibration;
    NoiseAnalysisOptions analysis;
    std::string output;    ///< report JSON (noise_analysis_json)
    std::string nedt_map;  ///< EXR nedt_k, temporal_noise_counts; "" = none (needs calibration)
    bool force = false;    ///< existing outputs may be replaced (OutputGuard)
};

/// Checks the outputs against the inputs (OutputGuard: OutputConflict before any work), loads,
/// analyses and writes the report (and the NEDT map when there is a calibration). Throws
/// tirpol::Error for a stack or calibration that does not read or does not fit.
NoiseAnalysis run_noise_analysis(const NoiseRunOptions& options);

/// The NEDT line (with a calibration) and the 3D-noise line in counts naming the report `output`.
std::string noise_analysis_text(const NoiseAnalysis& analysis, const std::string& output);

}  // namespace tirpol::calibration
