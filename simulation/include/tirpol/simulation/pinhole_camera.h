#pragma once
/// \file pinhole_camera.h
/// A pinhole camera with OpenCV's intrinsics and distortion (Brown–Conrady k1 k2 p1 p2 k3, rational
/// k4 k5 k6, thin prism s1..s4, as in OpenCV's calib3d "Camera Calibration and 3D Reconstruction").
/// In this class pixel (u, v) has its origin at the top-left corner of the top-left pixel, u to the
/// right, v down, so pixel centres are at +0.5 — the renderer samples pixel (x, y) over [x, x+1).
/// OpenCV (and a calibrated camera model file, core/camera_model.h) puts the *centre* of the
/// top-left pixel at (0, 0): from_model() adds the half pixel, so a world point that
/// cv::projectPoints sends to (u, v) lands at the centre of pixel (round(u), round(v)) of the
/// render. Camera axes follow OpenCV: x right, y down, z forward.

#include <optional>

#include "tirpol/core/camera_model.h"
#include "tirpol/core/config.h"
#include "tirpol/core/geometry.h"
#include "tirpol/core/stokes.h"

namespace tirpol::simulation {

struct CameraIntrinsics {
    double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;            ///< pixels
    double k1 = 0.0, k2 = 0.0, p1 = 0.0, p2 = 0.0, k3 = 0.0;  ///< OpenCV "standard" model
    double k4 = 0.0, k5 = 0.0, k6 = 0.0;                      ///< rational model denominators
    double s1 = 0.0, s2 = 0.0, s3 = 0.0, s4 = 0.0;            ///< thin prism
};

class PinholeCamera {
public:
    /// `world_from_camera` has the camera's x (right), y (down), z (forward) axes as columns.
    PinholeCamera(int width, int height, CameraIntrinsics intrinsics, Vec3 position,
                  Mat3 world_from_camera);

    /// From the `camera:` mapping of a scene file (docs/scene-format.md). Errors name
    /// file:line:field.
    static PinholeCamera from_config(const ConfigNode& node);

    /// The calibrated camera: a model file's intrinsics and distortion (OpenCV pixel convention,
    /// converted here) at `pose` (x_camera = R·x_world + t).
    static PinholeCamera from_model(const CameraModel& model, const CameraPose& pose);

    /// Camera at `position` looking at `target`, with `up` defining the image's upward direction.
    static Mat3 look_at(const Vec3& position, const Vec3& target, const Vec3& up);

    int width() const { return m_width; }
    int height() const { return m_height; }
    const CameraIntrinsics& intrinsics() const { return m_intrinsics; }
    const Vec3& position() const { return m_position; }
    const Mat3& world_from_camera() const { return m_world_from_camera; }

    /// A copy at another resolution: intrinsics scale with the image so the field of view is kept.
    PinholeCamera resized(int width, int height) const;
    /// A copy moved rigidly by `rotation` (world) about the world origin.
    PinholeCamera rotated(const Mat3& rotation) const;

    /// Unit world direction of the ray through image point (u, v) in pixels, distortion removed
    /// exactly (the inverse of project(), to ~1e-12 px).
    Vec3 ray_direction(double u, double v) const;

    /// Image point (u, v) (this class's corner-origin pixels) of a world point, with distortion;
    /// nullopt for a point on or behind the camera plane.
    std::optional<Eigen::Vector2d> project(const Vec3& world_point) const;

    /// The lens as a core CameraModel (OpenCV pixel convention), e.g. to write it to a file.
    const CameraModel& lens_model() const { return m_lens; }
    /// The pose as a core CameraPose.
    CameraPose pose() const;

    /// Stokes frame of light arriving at the camera along −`direction`: reference axis = the
    /// image's +x (camera right) projected onto the wavefront, 90° toward the image top
    /// (ARCHITECTURE.md).
    StokesFrame image_frame(const Vec3& direction) const;

private:
    int m_width, m_height;
    CameraIntrinsics m_intrinsics;
    CameraModel m_lens;  ///< the same lens in OpenCV's centre-origin convention, used for the maths
    Vec3 m_position;
    Mat3 m_world_from_camera;
};

}  // namespace tirpol::simulation
