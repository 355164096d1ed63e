#pragma once
/// \file calibration_chain.h
/// The order of the calibration steps, defined once: capture sessions by role → radiometric
/// calibration (counts → radiance, bad pixels) → polarimetric calibration (wire-grid τ/B, analyzer
/// model) → Stokes per scene session (reduce_session: offset, radiance, wire-grid removal, W⁺,
/// uncertainties) → polarized emissivity (paper eq 17). The CLI's calibrate, reduce and
/// extract-emissivity commands, the demo, the digital twin and the Python package all run this
/// list; a new step is one entry in calibration_steps() plus its function (docs/calibration.md).
///
/// `tirpol calibrate radiometric` and `tirpol calibrate polarimetric` from sessions to files: the
/// chain step (run_calibration_chain), the files it writes, and the text summary of each.
///
/// `tirpol reduce` for a rotating-polarizer session: with a radiometric calibration the whole
/// chain (run_calibration_chain) to a calibrated Stokes EXR, without one the counts quick look
/// (reduce_session_counts); the EXR, the PNG quick looks, and the summary of what was written.

#include <array>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tirpol/calibration/analyzer.h"
#include "tirpol/calibration/emissivity_extraction.h"
#include "tirpol/calibration/polarimetric_file.h"
#include "tirpol/calibration/radiometric.h"
#include "tirpol/calibration/session_calibration.h"
#include "tirpol/core/image.h"

namespace tirpol::calibration {

/// What the chain starts from: the sessions by the role they play, and each step's options. A step
/// whose inputs are absent does not run.
struct ChainInputs {
    /// The band of the radiometric calibration and of eq 17 (L_BB of a contact temperature).
    Band band{8.0, 14.0};
    /// Radiometric step: sessions of blackbody (or temperature-tagged shutter) records taken
    /// without the polarizer, one camera (several camera temperatures for
    /// RadiometricOptions::fpa_degree ≥ 1).
    std::vector<std::filesystem::path> blackbody_sessions;
    RadiometricOptions radiometric_options;
    /// Also residuals per set-point, NEDT and their warnings (assess_calibration).
    bool assess_quality = false;
    /// Polarimetric step: a session of blackbody records through the polarizer (and known-source
    /// repeats). Empty: none, the reduction uses the ideal analyzer at the session's angles.
    std::filesystem::path polarimetric_session;
    /// The polarizer's datasheet, used when that session has no known-source records.
    std::optional<DatasheetAnalyzer> datasheet;
    /// Reduction step: sessions of polarizer (scene) records, one Stokes image each.
    std::vector<std::filesystem::path> scene_sessions;
    SessionReductionOptions reduction;
    /// Emissivity step: the regions of each Stokes image, one entry per image or one for all.
    std::vector<EmissivityRois> rois;
};

/// What the chain makes, in step order. Products the caller already has (a calibration read from
/// its file, a Stokes EXR) are given to run_calibration_chain and their step is skipped.
struct ChainProducts {
    std::optional<RadiometricCalibration> radiometric;
    std::optional<CalibrationQuality> quality;  ///< with ChainInputs::assess_quality
    std::optional<PolarimetricCalibration> polarimetric;
    std::vector<Image> stokes;  ///< per scene session, in order
    std::vector<std::vector<EmissivityResult>>
        emissivity;  ///< per Stokes image, one row per target
};

/// The calibrations of earlier runs from their files (`calibrate radiometric -o CAL.exr`,
/// `calibrate polarimetric -o POL.yaml`), as products to start the chain from; an empty path: none.
ChainProducts read_calibration_products(const std::filesystem::path& radiometric_exr,
                                        const std::filesystem::path& polarimetric_yaml = {});

/// One step of the chain: its name, what it needs and makes (in words, for errors and docs), when
/// it is due (its inputs given, its product not yet made) and its function.
struct CalibrationStep {
    std::string_view name;
    std::string_view needs;
    std::string_view makes;
    bool (*due)(const ChainInputs&, const ChainProducts&);
    void (*run)(const ChainInputs&, ChainProducts&);
};

/// The steps in the order they run.
const std::vector<CalibrationStep>& calibration_steps();

/// Called before each step that runs (the twin names and times its stages with it).
using BeforeCalibrationStep = std::function<void(const CalibrationStep&)>;

/// Runs every due step in order, starting from `given`. Throws tirpol::Error naming the step when a
/// step lacks what it needs (a reduction without a radiometric calibration, regions without Stokes
/// images, a number of region sets that is neither 1 nor the number of images) and the errors of
/// the step's function.
ChainProducts run_calibration_chain(const ChainInputs& inputs, ChainProducts given = {},
                                    const BeforeCalibrationStep& before_step = {});

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

/// The session, the calibration files ("" calibration = counts quick look; the other options
/// then must stay off), the reduction switches and the files to write.
struct SessionToStokesOptions {
    std::string session;
    std::string calibration;   ///< radiometric calibration EXR, or ""
    std::string polarimetric;  ///< polarimetric calibration YAML, or ""
    std::string output;        ///< Stokes EXR
    std::string quicklooks;    ///< folder for S0/S1/S2/DoLP/AoP PNGs, or ""
    bool update_offset = false;
    bool drift_correction = false;
    bool slar = false;
    bool other_camera = false;
    double max_saturated_fraction = 0.01;
};

/// The drift correction applied, from the Stokes EXR's attributes.
struct DriftSummary {
    std::string source;
    double min_shift_counts = 0.0, max_shift_counts = 0.0;
    std::size_t records = 0;
    double max_sigma_counts = 0.0;
};

/// What session_to_stokes wrote.
struct SessionToStokes {
    std::string output;
    bool counts_quicklook = false;  ///< no calibration: counts, not radiance
    int width = 0, height = 0;
    ChannelStats s0, dolp;
    int saturated_pixels = 0;
    int unrealizable_pixels = 0;                      ///< calibrated reduction only
    std::optional<std::string> calibration_warnings;  ///< calibrated reduction only
    std::optional<DriftSummary> drift;                ///< with drift_correction
};

/// The quick-look file names of a Stokes folder, for output guards.
inline constexpr const char* kStokesQuicklookFiles[] = {"S0.png", "S1.png", "S2.png", "DoLP.png",
                                                        "AoP.png"};

/// Reduces the session and writes the Stokes EXR and the quick looks asked for. Throws
/// tirpol::Error naming the session or calibration for what does not read or fit.
SessionToStokes session_to_stokes(const SessionToStokesOptions& options);

/// What `tirpol reduce` checks before any work: without a calibration the calibrated-reduction
/// switches (polarimetric, update_offset, drift_correction, slar, other_camera) must stay off
/// (tirpol::OptionValueError naming the first one given), and no output may replace an input or,
/// unless `force`, an existing file (OutputGuard).
void check_session_to_stokes(const SessionToStokesOptions& options, bool force);

/// The summary: for a counts quick look its label and a line in counts; else the calibration
/// warnings, the drift correction and a line in radiance.
std::string session_to_stokes_text(const SessionToStokes& reduction);

}  // namespace tirpol::calibration
