#pragma once
/// \file stokes_frame.h
/// Reference frames of Stokes vectors and the rotation between them (paper §2.3.3, eqs 7–11).
///
/// A StokesFrame is a propagation direction k and a reference axis x ⟂ k (polarizer angle 0°); the
/// 90° axis is y = k × x, so (x, y, k) is right-handed and angles grow counter-clockwise for an
/// observer looking into the oncoming light. In the world frame of a ray (`world_frame`), x is
/// horizontal: x = up × k, normalized — the paper's "P" axis; its "S" (vertical) axis is y. For an
/// upright camera this is the image frame (0° along +x rows, 90° toward the top of the image), and
/// for a horizontal surface it is the s/p frame of reflection (x = s, perpendicular to the plane of
/// incidence). `surface_frame(k, n)` is the same construction with the surface normal n as "up".

#include "tirpol/core/geometry.h"
#include "tirpol/core/mueller.h"
#include "tirpol/core/stokes.h"

namespace tirpol {

struct StokesFrame {
    Vec3 propagation;  ///< unit direction of travel of the light
    Vec3 reference;    ///< unit axis of 0° polarization, perpendicular to `propagation`

    /// The 90° axis, propagation × reference.
    Vec3 second_axis() const { return propagation.cross(reference); }
};

/// Frame whose reference axis is `hint` projected onto the plane normal to `propagation`.
/// Where the hint is (nearly) parallel to the propagation, a fixed fallback axis is used, so the
/// result is always a valid frame (never a division by a vanishing norm).
StokesFrame frame_from_reference(const Vec3& propagation, const Vec3& hint);

/// World frame of a ray: reference axis horizontal, up × k (the paper's P axis).
StokesFrame world_frame(const Vec3& propagation, const Vec3& up = world_up());

/// s/p frame of a ray at a surface with normal `normal`: reference axis n × k (the s direction,
/// perpendicular to the plane of incidence/emission).
StokesFrame surface_frame(const Vec3& propagation, const Vec3& normal);

/// Angle (radians, counter-clockwise looking into the beam) from `from`'s reference axis to `to`'s.
/// Both frames must share their propagation direction. atan2-based, defined everywhere.
double frame_rotation_angle(const StokesFrame& from, const StokesFrame& to);

/// Re-expresses a Stokes vector given in `from` in the frame `to` (same propagation).
StokesVector change_frame(const StokesVector& s, const StokesFrame& from, const StokesFrame& to);

/// Mueller matrix `m` that maps Stokes in `in_from` to Stokes in `out_from`, re-expressed to map
/// `in_to` → `out_to` (paper eq 12: M_αe · M · M_αi).
MuellerMatrix change_frame(const MuellerMatrix& m, const StokesFrame& in_from,
                           const StokesFrame& in_to, const StokesFrame& out_from,
                           const StokesFrame& out_to);

/// The paper's eqs 7–10 literally: rotation angle α from the global Stokes geometry (S axis =
/// global up) to the surface-relative one (S axis = surface normal) for light travelling along `v`.
/// Equal to frame_rotation_angle(world_frame(v, up), surface_frame(v, normal)) modulo π; kept as an
/// independent implementation for tests and readers of the paper.
double paper_rotation_angle(const Vec3& v, const Vec3& normal, const Vec3& up = world_up());

}  // namespace tirpol
