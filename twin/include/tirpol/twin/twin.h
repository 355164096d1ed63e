#pragma once
/// \file twin.h
/// The digital twin, end to end: a paper scene is rendered, the renderer's sensor model
/// plays the camera (served over GigE Vision on loopback) and tirpol-stage-sim's engine plays the
/// polarizer mount (APT or Elliptec bytes on a pseudo-terminal, opened through the real serial
/// driver); `run_capture` records the sessions, calibration reduces them to Stokes, the flat black
/// paint's polarized emissivity is extracted over view angles and fitted, the scene is rendered
/// again with the fitted paint and the comparison report is written. A module of its own
/// (tirpol::twin) because it wires simulation to acquisition, which must not depend on each other;
/// the CLI's demo step and the Python bindings only call run_twin() and print twin_summary().
///
/// The twin's camera geometry: the truth camera is the nominal one (the scene's pinhole
/// at the surveyed position) with a realistic lens — barrel distortion, principal point off centre,
/// fx ≠ fy — and a pose error. The twin recovers both as a field user does: the library calls
/// behind `tirpol calibrate geometric` on frames of a heated checkerboard filmed through the
/// camera's detector, and behind `tirpol calibrate pose` on the surveyed corners of the panels with
/// their pixel positions; the comparison then renders through the recovered camera.
///
/// Blackbody set-points that bracket what the twin's camera will see. The radiometric calibration
/// (polarizer out of the beam) maps counts to the radiance at the detector, so its set-points must
/// span the detector radiance of the scene seen *through* the polarizer, ½(τ + τ_min)S0 ± ½(τ −
/// τ_min)√(S1² + S2²) plus the grid's reflected and emitted background (Chipman, Lam & Young 2018
/// eq 6.35, as the sensor model); the polarimetric calibration (blackbody through the polarizer)
/// must span the scene's S0. A calibration that does not span them extrapolates, and the report
/// says so.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/core/camera_model.h"
#include "tirpol/core/image.h"
#include "tirpol/core/radiometry.h"
#include "tirpol/report/registration.h"
#include "tirpol/report/verdict.h"
#include "tirpol/simulation/pinhole_camera.h"
#include "tirpol/simulation/scene.h"
#include "tirpol/simulation/sensor_model.h"
#include "tirpol/twin/instrument.h"

namespace tirpol::twin {

/// The coldest and warmest blackbody the twin's laboratory may use: an extended-area source cooled
/// to −100 °C (a cryogenically cooled plate; thermo-electric ones reach about −40 °C) and +100 °C.
inline constexpr double kColdestBlackbodyK = 173.15;
inline constexpr double kWarmestBlackbodyK = 373.15;
/// Margin on each side of the expected range, in brightness temperature.
inline constexpr double kSetpointMarginK = 2.0;

struct BlackbodySetpoints {
    std::vector<double>
        radiometric_k;  ///< three, polarizer out: span the detector radiance through the polarizer
    std::vector<double> polarimetric_k;  ///< two, through the polarizer: span the scene's S0
    double detector_radiance_min = 0.0, detector_radiance_max = 0.0;  ///< expected, W/(m²·sr)
    double scene_s0_min = 0.0, scene_s0_max = 0.0;  ///< of the truth renders, W/(m²·sr)
    /// Empty when both ranges are covered with margin; otherwise why not (a set-point was clamped
    /// to the laboratory's blackbody range).
    std::string limitation;
};

/// Set-points from the truth renders' S0, S1, S2 (finite pixels of every view) through `sensor`'s
/// analyzer and grid background, in `band`, with kSetpointMarginK on each side, clamped to
/// [kColdestBlackbodyK, kWarmestBlackbodyK]. Throws tirpol::Error when no render has a finite
/// pixel.
BlackbodySetpoints blackbody_setpoints(const std::vector<Image>& truth,
                                       const simulation::SensorModel& sensor, const Band& band);

/// The nominal camera's intrinsics with the twin's realistic lens (an uncooled LWIR core behind a
/// small germanium lens): k1 −0.30, k2 0.12, p1 0.0008, p2 −0.0005, k3 0, fy = 1.004 fx, the
/// principal point 3.1 % of the width right and 2.4 % of the height up of the nominal one.
simulation::PinholeCamera with_realistic_lens(const simulation::PinholeCamera& nominal);

/// The camera moved by the twin's pose error: 0.8° about the world axis (0.4, 1, 0.3), and
/// (+4, −6, +3) cm — a tripod set up by a tape measure and a compass.
simulation::PinholeCamera with_pose_error(const simulation::PinholeCamera& camera);

struct CameraGeometryOptions {
    int board_views = 25;  ///< frames of the heated checkerboard filmed for the lens
    int board_spp = 64;    ///< samples per pixel of those frames
    /// The board is tilted 20° to this toward the camera: steep views make the focal length
    /// observable on a small detector (at 160×120, 40° leaves fx uncertain by 1 %, 55° by 0.2 %).
    double board_max_tilt_deg = 55.0;
    /// The board is also rolled about the optical axis by up to ± this: at 160×120 with ~0.09 px of
    /// corner noise, rolls of ±25° leave cx uncertain by 3.5 px (1σ), ±180° by 1.4 px (see
    /// docs/twin.md, "Known limits").
    double board_roll_spread_deg = 180.0;
    /// `--fix-k3`: a 34° lens on a 160-pixel detector does not constrain k3
    /// (docs/camera-geometry.md: its σ exceeds it), so the field user keeps it at 0.
    bool fix_k3 = true;
    double pick_sigma_px =
        0.1;          ///< pixel noise of the control points (centroids of heated markers)
    int threads = 0;  ///< render threads (0: all cores)
};

struct CameraGeometryRecovery {
    CameraModel true_lens, lens;  ///< truth and recovered (OpenCV pixel convention)
    std::vector<std::string> lens_parameter_names;  ///< fx fy cx cy k1 …, the order of lens.std_dev
    CameraPose true_pose, pose;  ///< truth and recovered, x_camera = R x_world + t
    CameraPose nominal_pose;     ///< where the user believed the camera was
    int board_frames = 0;        ///< frames filmed (lens.views of them showed the board)
    int control_points = 0;      ///< surveyed points given to the pose estimate
    double rotation_error_deg = 0.0, position_error_m = 0.0;  ///< recovered vs true pose
    double nominal_rotation_error_deg = 0.0,
           nominal_position_error_m = 0.0;  ///< nominal vs true pose
    std::filesystem::path lens_file, pose_file, control_points_file;

    /// The recovered camera, for rendering the simulation onto the measured pixel grid.
    simulation::PinholeCamera camera() const {
        return simulation::PinholeCamera::from_model(lens, pose);
    }
};

/// Films `HeatedBoard` views through `truth`'s lens (rendered, then the sensor model of `world`
/// with the polarizer out of the beam), calibrates the lens from the frames, projects the corners
/// of the `panel_*` objects of `field` through `truth` as the control points' pixels (with
/// options.pick_sigma_px noise) and estimates the pose with the recovered lens. Writes the frames,
/// the camera model, the control points CSV and the pose under `dir`.
CameraGeometryRecovery recover_camera_geometry(const simulation::Scene& field,
                                               const simulation::PinholeCamera& truth,
                                               const simulation::PinholeCamera& nominal,
                                               const TwinWorld& world,
                                               const std::filesystem::path& dir,
                                               const CameraGeometryOptions& options = {});

/// One camera position for the emissivity series (the scene's own camera is the first view).
struct TwinView {
    double position[3] = {0.0, -6.0, 1.6};
    double look_at[3] = {0.0, 0.0, 1.1};
};

struct TwinOptions {
    std::filesystem::path out_dir;
    std::filesystem::path
        scene_file;  ///< empty: config/scenes/panels_night.yaml of the source tree
    int width = 160, height = 120, spp = 8;
    int frames_per_angle =
        16;  ///< frames averaged per polarizer angle (blackbody steps: twice as many)
    /// Camera positions; the first is the scene's (the report compares that view). Empty: the
    /// scene's camera plus two higher ones, so the panel is seen at three view angles.
    std::vector<TwinView> views;
    StageProtocol stage_protocol = StageProtocol::Apt;
    bool gige =
        true;         ///< serve the camera over GigE Vision (false: the in-process SimulatedCamera)
    int threads = 0;  ///< render threads (0: all cores)
    std::string target = "panel_flat_black_paint";         ///< the panel whose paint is fitted
    std::string reflector = "panel_diffuse_ir_reflector";  ///< downwelling reference (paper eq 17)
    std::string tool_version = "tirpol";  ///< written into the report's provenance ("tirpol X.Y.Z")
    /// Changes the truth only (e.g. a material's roughness), not the scene the fitted render uses:
    /// what a real scene differs by from its model. The report should flag the regions it touches.
    /// Null: none.
    std::function<void(simulation::Scene&)> perturb_truth;
    /// Compare against a render with the fitted target paint (true, the chain's point). False: the
    /// comparison render keeps every material of the scene file, so the only difference between
    /// model and truth is `perturb_truth` — the report's false alarms and detections are then its
    /// own, free of the fit's method bias (eq 17's, docs/twin.md).
    bool render_fitted_target = true;
    /// False-alarm rate per region and power of the report's region-mean tests.
    report::TestDesign report_design;
    /// Another run of the same twin: the renders' sampling seed (the scene file's otherwise) and
    /// the camera's noise seed (twin_sensor's otherwise), so that runs can be compared as
    /// independent.
    std::optional<std::uint64_t> seed;
};

/// Extracted polarized emissivity of the target in one view (plane-of-emission frame, σ = 1
/// standard uncertainty). Two references separate the instrument from the method: eq 17 applied to
/// the truth render (`method_*`: a perfect instrument, so eps − method is the instrument chain's
/// error) and the paint's own directional emissivity (`true_*`: method − true is eq 17's bias, from
/// a downwelling that is not uniform — docs/twin.md).
struct TwinEmissivity {
    double view_angle_deg = 0.0;
    double eps_s0 = 0.0, eps_s0_std = 0.0, eps_s1 = 0.0,
           eps_s1_std = 0.0;  ///< measured sessions
    double method_s0 = 0.0, method_s0_std = 0.0, method_s1 = 0.0,
           method_s1_std = 0.0;           ///< truth render
    double true_s0 = 0.0, true_s1 = 0.0;  ///< the true paint's directional emissivity at that angle
};

struct TwinParameter {
    std::string name;
    double truth = 0.0, fitted = 0.0;
    double std_uncertainty = 0.0;  ///< of `fitted`
    bool fixed = false;
};

/// The fit through the renderer (fitting/render_fit.h) of the same paint, beside eq 17's: the
/// measured Stokes of the target in every view against renders of the scene with candidate n and σ.
struct TwinRenderFit {
    std::vector<TwinParameter>
        parameters;  ///< n and σ (k, ρ_D and the rest as in the scene's paint)
    double reduced_chi2 = 0.0;
    int dof = 0;
    int renders = 0;
    bool usable = false;
    std::vector<std::string> warnings;
};

/// Agreement of measured and simulated Stokes in one region (from the comparison report).
struct TwinRegionAgreement {
    std::string name;
    std::size_t pixels = 0;
    report::QuantityVerdict quantities[3];  ///< S0, S1, S2: region-mean test and σ diagnostic
    report::Agreement verdict =
        report::Agreement::NoData;  ///< ExceedsNoise when any quantity exceeds
};

/// Measured vs the truth render, target ROI means of S0 S1 S2 (W/(m²·sr)).
struct TwinStokesCheck {
    double measured[3] = {0, 0, 0}, truth[3] = {0, 0, 0};
    double std_error[3] = {
        0, 0, 0};  ///< standard error of the mean difference (ROI scatter of measured − truth)
    double std_error_temporal[3] = {
        0, 0, 0};  ///< of which temporal noise alone (the reduction's *_std channels)
};

struct TwinResult {
    std::string
        camera_transport;  ///< "GigE Vision on 127.0.0.1 (aravis://…)" or the fallback's reason
    std::string stage_description;
    std::vector<std::filesystem::path> sessions;
    TwinStokesCheck target_stokes;  ///< first view
    std::vector<TwinEmissivity> emissivity;
    std::vector<TwinParameter> parameters;
    double reduced_chi2 = 0.0;
    int dof = 0;               ///< of the eq-17 fit
    TwinRenderFit render_fit;  ///< the same paint fitted through the renderer
    CameraGeometryRecovery
        camera;  ///< the field camera's lens and pose (view 0), true and recovered
    report::Registration
        registration;  ///< of the comparison: by the recovered camera model, with the residual
    std::vector<TwinRegionAgreement> regions;
    std::string report_summary;    ///< the report's Summary paragraph
    BlackbodySetpoints blackbody;  ///< the calibration set-points, derived from the truth renders
    double calibration_outside_fraction =
        0.0;  ///< of view 0's reduced frames (the reduction's attribute)
    std::filesystem::path report_html, fitted_material, measured_exr, simulated_exr;
    std::filesystem::path
        report_regions;  ///< the report's regions as YAML (for `tirpol compare --rois`)
    std::filesystem::path
        fit_comparison;  ///< fit/paint_fits.txt: eq 17 and the renderer fit side by side
    std::map<std::string, double> seconds;  ///< per stage
};

/// Runs the whole chain. Throws tirpol::Error naming the stage that failed.
TwinResult run_twin(const TwinOptions& options);

/// The paint's parameters from eq 17's route and from the fit through the renderer, side by side
/// (true value, each fit's value ± 1σ, χ²/dof): lines of the summary and the file
/// fit/paint_fits.txt.
std::string paint_fit_comparison(const TwinResult& r);

/// The demo's text summary: devices, target Stokes vs truth, emissivity, fit, per-region agreement,
/// times.
std::string twin_summary(const TwinResult& r);

}  // namespace tirpol::twin
