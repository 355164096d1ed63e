#pragma once
/// \file camera.h
/// A pinhole camera with OpenCV-style intrinsics and distortion (Brown–Conrady k1 k2 p1 p2 k3, as in
/// OpenCV's calib3d "Camera Calibration and 3D Reconstruction" model). Pixel (u, v) has its origin at
/// the top-left corner of the top-left pixel, u to the right, v down; pixel centres are at +0.5.
/// Camera axes follow OpenCV: x right, y down, z forward.

#include <optional>

#include "tirpol/core/config.h"
#include "tirpol/core/geometry.h"
#include "tirpol/core/stokes_frame.h"

namespace tirpol::simulation {

struct CameraIntrinsics {
    double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;  ///< pixels
    double k1 = 0.0, k2 = 0.0, p1 = 0.0, p2 = 0.0, k3 = 0.0;
};

class Camera {
public:
    /// `world_from_camera` has the camera's x (right), y (down), z (forward) axes as columns.
    Camera(int width, int height, CameraIntrinsics intrinsics, Vec3 position, Mat3 world_from_camera);

    /// From the `camera:` mapping of a scene file (docs/scene-format.md). Errors name file:line:field.
    static Camera from_config(const ConfigNode& node);

    /// Camera at `position` looking at `target`, with `up` defining the image's upward direction.
    static Mat3 look_at(const Vec3& position, const Vec3& target, const Vec3& up);

    int width() const { return m_width; }
    int height() const { return m_height; }
    const CameraIntrinsics& intrinsics() const { return m_intrinsics; }
    const Vec3& position() const { return m_position; }
    const Mat3& world_from_camera() const { return m_world_from_camera; }

    /// A copy at another resolution: intrinsics scale with the image so the field of view is kept.
    Camera resized(int width, int height) const;
    /// A copy moved rigidly by `rotation` (world) about the world origin.
    Camera rotated(const Mat3& rotation) const;

    /// Unit world direction of the ray through image point (u, v) in pixels, distortion removed.
    Vec3 ray_direction(double u, double v) const;

    /// Stokes frame of light arriving at the camera along −`direction`: reference axis = the image's +x
    /// (camera right) projected onto the wavefront, 90° toward the image top (ARCHITECTURE.md).
    StokesFrame image_frame(const Vec3& direction) const;

private:
    int m_width, m_height;
    CameraIntrinsics m_intrinsics;
    Vec3 m_position;
    Mat3 m_world_from_camera;
};

}  // namespace tirpol::simulation
