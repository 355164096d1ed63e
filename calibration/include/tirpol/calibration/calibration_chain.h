#pragma once
/// \file calibration_chain.h
/// The order of the calibration steps, defined once: capture sessions by role → radiometric
/// calibration (counts → radiance, bad pixels) → polarimetric calibration (wire-grid τ/B, analyzer
/// model) → Stokes per scene session (reduce_session: offset, radiance, wire-grid removal, W⁺,
/// uncertainties) → polarized emissivity (paper eq 17). The CLI's calibrate, reduce and
/// extract-emissivity commands, the demo, the digital twin and the Python package all run this
/// list; a new step is one entry in calibration_steps() plus its function (docs/calibration.md).

#include <filesystem>
#include <functional>
#include <optional>
#include <string_view>
#include <vector>

#include "tirpol/calibration/calibration_quality.h"
#include "tirpol/calibration/datasheet_analyzer.h"
#include "tirpol/calibration/emissivity_extraction.h"
#include "tirpol/calibration/session_calibration.h"

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

}  // namespace tirpol::calibration
