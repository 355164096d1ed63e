#pragma once
/// \file camera_geometry.h
/// The twin's camera geometry: the truth camera is the nominal one (the scene's pinhole
/// at the surveyed position) with a realistic lens — barrel distortion, principal point off centre,
/// fx ≠ fy — and a pose error. The twin recovers both as a field user does: the library calls
/// behind `tirpol calibrate geometric` on frames of a heated checkerboard filmed through the
/// camera's detector, and behind `tirpol calibrate pose` on the surveyed corners of the panels with
/// their pixel positions; the comparison then renders through the recovered camera.

#include <filesystem>

#include "tirpol/core/camera_model.h"
#include "tirpol/simulation/pinhole_camera.h"
#include "tirpol/simulation/scene.h"
#include "tirpol/twin/instrument.h"

namespace tirpol::twin {

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

}  // namespace tirpol::twin
