#include "tirpol/calibration/calibration_chain.h"

#include "tirpol/core/error.h"

namespace tirpol::calibration {

namespace {

bool radiometric_due(const ChainInputs& in, const ChainProducts& p) {
    return !in.blackbody_sessions.empty() && !p.radiometric;
}

void radiometric(const ChainInputs& in, ChainProducts& p) {
    CalibrationQuality quality;
    p.radiometric =
        calibrate_radiometric_sessions(in.blackbody_sessions, in.band, in.radiometric_options,
                                       in.assess_quality ? &quality : nullptr);
    if (in.assess_quality) p.quality = std::move(quality);
}

bool polarimetric_due(const ChainInputs& in, const ChainProducts& p) {
    return !in.polarimetric_session.empty() && !p.polarimetric;
}

const RadiometricCalibration& needed_radiometric(const ChainProducts& p, std::string_view step) {
    if (!p.radiometric)
        fail(
            "calibration chain, step '{}': needs a radiometric calibration (blackbody sessions or "
            "a calibration "
            "file)",
            step);
    return *p.radiometric;
}

void polarimetric(const ChainInputs& in, ChainProducts& p) {
    p.polarimetric = calibrate_polarimetric_session(
        in.polarimetric_session, needed_radiometric(p, "polarimetric"), in.datasheet);
}

bool reduce_due(const ChainInputs& in, const ChainProducts& p) {
    return !in.scene_sessions.empty() && p.stokes.empty();
}

void reduce(const ChainInputs& in, ChainProducts& p) {
    const RadiometricCalibration& radiometric = needed_radiometric(p, "reduce");
    for (const auto& dir : in.scene_sessions)
        p.stokes.push_back(reduce_session(
            dir, radiometric, p.polarimetric ? &*p.polarimetric : nullptr, in.reduction));
}

bool emissivity_due(const ChainInputs& in, const ChainProducts& p) {
    return !in.rois.empty() && p.emissivity.empty();
}

void emissivity(const ChainInputs& in, ChainProducts& p) {
    if (p.stokes.empty())
        fail(
            "calibration chain, step 'emissivity': needs Stokes images (scene sessions or a Stokes "
            "EXR)");
    if (in.rois.size() != 1 && in.rois.size() != p.stokes.size())
        fail(
            "calibration chain, step 'emissivity': {} region sets for {} Stokes images; expected 1 "
            "or {}",
            in.rois.size(), p.stokes.size(), p.stokes.size());
    for (std::size_t i = 0; i < p.stokes.size(); ++i)
        p.emissivity.push_back(
            extract_emissivity(p.stokes[i], in.rois[in.rois.size() == 1 ? 0 : i], in.band));
}

}  // namespace

const std::vector<CalibrationStep>& calibration_steps() {
    static const std::vector<CalibrationStep> steps{
        {"radiometric", "blackbody sessions without the polarizer",
         "per-pixel counts → radiance, bad-pixel map (RadiometricCalibration)", radiometric_due,
         radiometric},
        {"polarimetric",
         "a session of blackbody records through the polarizer; the radiometric calibration",
         "wire-grid τ/B maps and the analyzer model (PolarimetricCalibration)", polarimetric_due,
         polarimetric},
        {"reduce", "scene sessions; the radiometric and (optional) polarimetric calibrations",
         "Stokes S0 S1 S2 DoLP AoP with uncertainties, one image per session", reduce_due, reduce},
        {"emissivity", "regions (IR reflector, targets); the Stokes images",
         "ε_S0, ε_S1, ε_S2 with 1σ per target (paper eq 17)", emissivity_due, emissivity},
    };
    return steps;
}

ChainProducts read_calibration_products(const std::filesystem::path& radiometric_exr,
                                        const std::filesystem::path& polarimetric_yaml) {
    ChainProducts p;
    if (!radiometric_exr.empty())
        p.radiometric = read_radiometric_calibration(radiometric_exr.string());
    if (!polarimetric_yaml.empty())
        p.polarimetric = read_polarimetric_calibration(polarimetric_yaml.string());
    if (p.radiometric && p.polarimetric)
        check_same_band(*p.radiometric, radiometric_exr.string(), *p.polarimetric,
                        polarimetric_yaml.string());
    return p;
}

ChainProducts run_calibration_chain(const ChainInputs& inputs, ChainProducts given,
                                    const BeforeCalibrationStep& before_step) {
    for (const CalibrationStep& step : calibration_steps()) {
        if (!step.due(inputs, given)) continue;
        if (before_step) before_step(step);
        step.run(inputs, given);
    }
    return given;
}

}  // namespace tirpol::calibration
