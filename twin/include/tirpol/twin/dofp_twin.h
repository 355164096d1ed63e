#pragma once
/// \file dofp_twin.h
/// The digital twin of a microgrid (division-of-focal-plane) camera, end to end: a scene is
/// rendered at the sensor's full resolution and seen through the renderer's DoFP sensor stage
/// (simulation/dofp_sensor.h: each pixel its own micro-polarizer and bolometer, drawn with a
/// manufacturing spread), served as a free-running GigE Vision camera in PolarizeMono16; the
/// flat-field rig (the blackbody open, then behind a reference polarizer on the simulated stage)
/// is recorded with `run_capture`, `calibrate_microgrid_sessions` fits every pixel, the scene is
/// captured and reduced per super-pixel, and the result is compared with the rendered truth: the
/// scene's Stokes per region (pulls) and the planted per-pixel analyzers (RMS of fitted − planted).

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "tirpol/simulation/dofp_sensor.h"
#include "tirpol/twin/instrument.h"

namespace tirpol::twin {

struct DofpTwinOptions {
    std::filesystem::path out_dir;
    std::filesystem::path scene_file;      ///< empty: config/scenes/panels_night.yaml
    int width = 64, height = 48, spp = 4;  ///< the focal plane (even) and the truth's samples
    /// The camera: Sony layout, 5 % transmission and responsivity spread, axis σ 1°, d 0.95 ±
    /// 0.015, 800 counts per W/(m² sr), NEDT 50 mK, 16 bits (DofpSensorSpec's defaults) unless
    /// changed.
    simulation::DofpSensorSpec sensor;
    ReferencePolarizer reference;
    int flat_frames = 16;   ///< frames averaged per flat-field record
    int scene_frames = 32;  ///< frames averaged in the scene record
    /// Reference polarizer angles of the flat field (≥ 3; Powell & Gruev's fit).
    std::vector<double> reference_angles_deg{0.0, 22.5, 45.0, 67.5, 90.0, 112.5, 135.0, 157.5};
    /// Blackbody temperatures behind the reference polarizer (one session each).
    std::vector<double> polarizer_blackbody_k{293.15, 323.15};
    StageProtocol stage_protocol = StageProtocol::Apt;
    bool gige =
        true;  ///< serve the camera over GigE Vision (false: the in-process SimulatedCamera)
    /// GenICam XML offering PolarizeMono16 (tests/data/genicam/polarized-fake-camera.xml); empty:
    /// the in-process camera, with the reason in `camera_transport`.
    std::filesystem::path genicam_xml;
    int threads = 0;  ///< render threads (0: all cores)
};

/// One region (an object's interior rectangle) of the scene, over its whole super-pixels,
/// W/(m² sr). `truth` is what this camera measures without noise and with its analyzers known
/// exactly: each pixel sees its own rendered Stokes through its planted analysis vector, each cell
/// reduced by W⁺ of its four; `footprint_truth` is the mean of the cells' four rendered pixels.
/// They differ by the IFOV error (the four analyzers of a cell see four places: a gradient biases
/// S1 and S2). σ is the standard error of the mean of measured − truth (its scatter over the
/// region: temporal noise, calibration residuals), so the pull tests the instrument chain, and
/// (truth − footprint)/σ states the IFOV bias in the same units.
struct DofpRegionCheck {
    std::string name;
    int super_pixels = 0;
    double measured[3] = {0, 0, 0}, truth[3] = {0, 0, 0}, footprint_truth[3] = {0, 0, 0};
    double sigma[3] = {0, 0, 0};
    double pull(int c) const { return (measured[c] - truth[c]) / sigma[c]; }
};

/// Fitted − planted per-pixel parameters over the good pixels.
struct DofpParameterRecovery {
    std::size_t pixels = 0;
    double axis_rms_deg = 0.0;             ///< RMS of fitted − planted axis θ_i
    double diattenuation_rms = 0.0;        ///< of d_i
    double gain_rel_rms = 0.0;             ///< of g_i/g_i,planted − 1, g_i = R_i·½·t_i
    double planted_axis_spread_deg = 0.0;  ///< RMS of planted − nominal axis (what was to find)
    double planted_diattenuation_spread = 0.0;  ///< σ of the planted d_i
    double planted_gain_rel_spread = 0.0;       ///< σ of g_i/mean − 1
};

struct DofpTwinResult {
    std::string camera_transport;  ///< "GigE Vision on 127.0.0.1 (aravis://…)" or the fallback's
    std::string stage_description;
    std::vector<std::filesystem::path> flat_sessions;
    std::filesystem::path scene_session, calibration_exr, measured_exr, truth_exr;
    std::string pixel_format;    ///< as the session records it
    double frame_rate_hz = 0.0;  ///< delivered by the camera over the scene capture
    std::vector<DofpRegionCheck> regions;
    double pull_rms = 0.0;  ///< over all regions and S0, S1, S2
    double pull_max_abs = 0.0;
    double pull_rms_nuc_only = 0.0;  ///< the same with the NUC alone (ideal analyzers)
    DofpParameterRecovery parameters;
    std::size_t bad_pixels = 0;  ///< found by the calibration (none planted)
    /// Over the regions' super-pixels: DoLP RMS error against the (exact-DoFP) truth, with the
    /// per-pixel calibration and with the NUC alone (ideal analyzers at the nominal pattern).
    double dolp_rms_per_pixel = 0.0, dolp_rms_nuc_only = 0.0;
    std::map<std::string, double> seconds;  ///< per stage
};

/// Runs the chain. Throws tirpol::Error naming the stage that failed.
DofpTwinResult run_dofp_twin(const DofpTwinOptions& options);

/// The run's text summary: devices, parameter recovery, per-region pulls, times.
std::string dofp_twin_summary(const DofpTwinResult& r);

}  // namespace tirpol::twin
