#pragma once
/// \file microgrid_run.h
/// What the CLI runs for a microgrid (division-of-focal-plane) camera: `tirpol demosaic` (one frame
/// file), `tirpol reduce` of a microgrid session and `tirpol calibrate microgrid`. Each takes file
/// paths and option text (strings, as the command line gives them), checks its outputs against its
/// inputs (OutputGuard) before any work, writes its files and returns a typed summary that its
/// `*_text` formats.

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "tirpol/calibration/microgrid_session.h"

namespace tirpol::calibration {

/// `tirpol demosaic INPUT -o OUTPUT`.
struct DemosaicRunOptions {
    std::string input, output;
    /// Analyzer angles of the 2×2 cell ("90,45,135,0") or "sony"; empty: the one an EXR records.
    std::string pattern;
    std::string method = "newton";   ///< super-pixel, bilinear or newton
    std::string channel = "counts";  ///< EXR channel holding the frame
    bool force = false;              ///< an existing output may be replaced (OutputGuard)
};

/// What run_demosaic wrote.
struct DemosaicRun {
    std::filesystem::path output;
    int width = 0, height = 0;
    DemosaicMethod method = DemosaicMethod::Newton;
    std::string pattern;  ///< the analyzer angles used, "90,45,135,0"
    std::string units;    ///< of S0, S1, S2 ("counts" for a PNG/TIFF)
    double s0_mean = 0.0, dolp_mean = 0.0;
    int unrealizable_pixels = 0;  ///< projected onto the physical cone
};

/// Reads the frame, reduces it (reduce_microgrid_file) and writes the Stokes EXR. Throws
/// tirpol::OptionValueError naming --pattern or --method for text that names no pattern or
/// method, OutputConflict for an output that would replace the input or (unless `force`) a file,
/// and tirpol::Error as reduce_microgrid_file does.
DemosaicRun run_demosaic(const DemosaicRunOptions& options);

/// "Stokes W×H (METHOD, pattern P): S0 mean …, DoLP mean …; N unrealizable pixel(s) projected →
/// OUTPUT" and a newline.
std::string demosaic_run_text(const DemosaicRun& run);

/// `tirpol reduce SESSION -o OUTPUT` for a session of a microgrid camera.
struct MicrogridReduceRunOptions {
    std::string session, output;
    std::string quicklooks;         ///< folder for S0/S1/S2/DoLP/AoP PNGs, or empty
    std::string pixel_calibration;  ///< per-pixel calibration EXR, or empty
    std::string method = "newton";  ///< demosaicing without a per-pixel calibration
    bool force = false;             ///< existing outputs may be replaced (OutputGuard)
};

/// What run_microgrid_reduction wrote.
struct MicrogridReduceRun {
    std::filesystem::path output;
    int width = 0, height = 0;
    int frames_averaged = 0;
    std::string pattern;  ///< the session's analyzer angles, "90,45,135,0"
    /// The demosaicing method's name, or "per-pixel calibration" (per super-pixel).
    std::string reduction;
    /// Of S0, S1, S2 (MicrogridSessionRecord::units): counts, the per-pixel calibration's Stokes
    /// units, or "(units not recorded)" for a calibration that does not state them.
    std::string units;
    double s0_mean = 0.0, dolp_mean = 0.0;
};

/// True when `session` has a manifest that reads and records a microgrid pattern; false for
/// anything else (a rotating-polarizer session, or one whose damage the reduction reports).
bool is_readable_microgrid_session(const std::filesystem::path& session);

/// Reduces the session (reduce_microgrid_session, with the per-pixel calibration when given) and
/// writes the Stokes EXR (attribute `pixel_calibration`: the calibration's path) and the quick
/// looks asked for. Throws tirpol::OptionValueError naming --method for an unknown method,
/// OutputConflict as run_demosaic does, tirpol::Error as reduce_microgrid_session does.
MicrogridReduceRun run_microgrid_reduction(const MicrogridReduceRunOptions& options);

/// "Stokes W×H (microgrid P, REDUCTION, N frame(s)): S0 mean … UNITS, DoLP mean … → OUTPUT".
std::string microgrid_reduce_run_text(const MicrogridReduceRun& run);

/// `tirpol calibrate microgrid SESSION... -o OUTPUT`.
struct MicrogridCalibrationRunOptions {
    std::vector<std::string> sessions;
    std::string output;
    std::string rsr;  ///< relative spectral response CSV, or empty: a flat band
    std::array<double, 2> band_um{8.0, 14.0};
    bool force = false;  ///< an existing output may be replaced (OutputGuard)
};

/// What run_microgrid_calibration made and wrote.
struct MicrogridCalibrationRun {
    std::filesystem::path output;
    MicrogridFlatFieldCalibration calibration;
};

/// Calibrates the camera from the sessions (calibrate_microgrid_sessions) and writes the per-pixel
/// calibration EXR (MicrogridPixelCalibration::to_image, attribute `band_um`: two reals LO HI).
/// Throws tirpol::OptionValueError naming --band-um unless 0 < LO < HI, OutputConflict as
/// run_demosaic does, tirpol::Error as calibrate_microgrid_sessions does.
MicrogridCalibrationRun run_microgrid_calibration(const MicrogridCalibrationRunOptions& options);

/// Records used, the NUC's gain spread and fit, the analyzers' diattenuation and axis error, the
/// bad pixels by kind, and the output path: five lines.
std::string microgrid_calibration_text(const MicrogridCalibrationRun& run);

}  // namespace tirpol::calibration
