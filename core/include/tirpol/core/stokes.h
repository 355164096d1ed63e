#pragma once
/// \file stokes.h
/// Stokes vectors S = (S0, S1, S2, S3) and the quantities derived from them. A Stokes vector is
/// always expressed in some StokesFrame (stokes_frame.h): S1 > 0 means polarized along the frame's
/// reference axis (polarizer angle 0°), S2 > 0 along +45° (counter-clockwise looking into the
/// beam), S3 > 0 right-circular in the observer's view. Units are those of S0 (radiance, counts,
/// ...).
///
/// Mueller matrices of standard elements, in the Stokes convention of stokes.h. Angles are the
/// element's axis angle measured counter-clockwise from the frame's reference axis, looking into
/// the beam (Collett, "Field Guide to Polarization", 2005, §§ "Mueller matrices"; Chipman, Lam &
/// Young, "Polarized Light and Optical Systems", 2018, ch. 6).
///
/// Reference frames of Stokes vectors and the rotation between them (paper §2.3.3, eqs 7–11).
///
/// A StokesFrame is a propagation direction k and a reference axis x ⟂ k (polarizer angle 0°); the
/// 90° axis is y = k × x, so (x, y, k) is right-handed and angles grow counter-clockwise for an
/// observer looking into the oncoming light. In the world frame of a ray (`world_frame`), x is
/// horizontal: x = up × k, normalized — the paper's "P" axis; its "S" (vertical) axis is y. For an
/// upright camera this is the image frame (0° along +x rows, 90° toward the top of the image), and
/// for a horizontal surface it is the s/p frame of reflection (x = s, perpendicular to the plane of
/// incidence). `surface_frame(k, n)` is the same construction with the surface normal n as "up".
///
/// Nominal polarizer (analyzer) angles as keys: the one rule by which a session record, an analyzer
/// position, a wire-grid calibration entry and an EXR channel name refer to "the same angle". Two
/// nominal angles are the same when they agree to the hundredth of a degree (plans write 0, 45.0,
/// 22.5; a float round trip through a file changes them far less). Angles are not wrapped: 0° and
/// 180° are different positions of the mount.

#include <Eigen/Core>
#include <cmath>
#include <complex>
#include <string>

#include "tirpol/core/geometry.h"

namespace tirpol {

using StokesVector = Eigen::Vector4d;

/// Unpolarized light of intensity `s0`.
inline StokesVector unpolarized(double s0) { return {s0, 0.0, 0.0, 0.0}; }

/// Partially linearly polarized light: intensity s0, degree of linear polarization `dolp` in [0,
/// 1], angle of polarization `aop_rad` from the frame's reference axis.
StokesVector linearly_polarized(double s0, double dolp, double aop_rad);

/// Degree of linear polarization √(S1²+S2²)/S0; 0 where S0 ≤ 0; NaN where S0, S1 or S2 is NaN.
double dolp(const StokesVector& s);

/// Degree of polarization √(S1²+S2²+S3²)/S0; 0 where S0 ≤ 0; NaN where a component is NaN.
double dop(const StokesVector& s);

/// Angle of linear polarization ½·atan2(S2, S1) in radians, in (−π/2, π/2].
double aop_rad(const StokesVector& s);

/// Angle of linear polarization in degrees mapped to [0, 180), the convention of the AoP image
/// channel.
double aop_deg_0_180(const StokesVector& s);

/// Physically realizable: S0 ≥ 0 and S0 ≥ √(S1²+S2²+S3²) within a relative tolerance `rel_tol`
/// of S0 (absolute `abs_tol` for S0 ≈ 0).
bool is_realizable(const StokesVector& s, double rel_tol = 1e-9, double abs_tol = 1e-300);

using MuellerMatrix = Eigen::Matrix4d;
using JonesMatrix = Eigen::Matrix2cd;

/// Rotation of the Stokes reference frame by `angle_rad` (counter-clockwise looking into the beam):
/// the paper's eq 11. For light polarized along the new reference axis, the result has S1 = S0.
MuellerMatrix frame_rotation(double angle_rad);

/// The element `m` physically rotated by `angle_rad`: R(−θ)·M·R(θ).
MuellerMatrix rotate_element(const MuellerMatrix& m, double angle_rad);

/// Ideal linear polarizer with its transmission axis at `axis_rad` (Malus's law).
MuellerMatrix linear_polarizer(double axis_rad);

/// Linear diattenuator (non-ideal polarizer): intensity transmittance `t_max` for light polarized
/// along the axis, `t_min` across it (Chipman et al. 2018, eq 6.35).
MuellerMatrix linear_diattenuator(double axis_rad, double t_max, double t_min);

/// Non-ideal polarizer given by its major transmittance and extinction ratio t_max/t_min (e.g. 400
/// for the paper's wire grid, §3.1).
MuellerMatrix polarizer_with_extinction(double axis_rad, double transmission,
                                        double extinction_ratio);

/// Linear retarder with fast axis at `fast_axis_rad` and retardance `retardance_rad` (Collett's
/// form; equals mueller_from_jones(diag(1, e^{−iδ})) for a horizontal fast axis, i.e. the exp(i(ωt
/// − kz)) time convention). A quarter-wave plate with its fast axis at +45° turns horizontal light
/// into S3 = +1, right-circular seen by the receiver as stokes.h defines it.
MuellerMatrix linear_retarder(double fast_axis_rad, double retardance_rad);

/// Partial depolarizer diag(1, a, a, a) with `a` in [0, 1].
MuellerMatrix depolarizer(double retained_fraction);

/// Mueller matrix of a Jones matrix, M_ij = ½·tr(σ_i J σ_j J†) with the Pauli basis that matches
/// stokes.h: σ0 = I, σ1 = diag(1, −1), σ2 = [[0,1],[1,0]], σ3 = [[0,−i],[i,0]] (Chipman et al.
/// eq 6.99).
MuellerMatrix mueller_from_jones(const JonesMatrix& j);

/// Cloude coherency matrix H = ¼·Σ m_ij (σ_i ⊗ σ_j*) (S. R. Cloude, Optik 75, 26–36, 1986).
/// Hermitian; a Mueller matrix is physically realizable iff H is positive semi-definite.
Eigen::Matrix4cd cloude_coherency(const MuellerMatrix& m);

/// Physically realizable: every eigenvalue of the Cloude coherency matrix ≥ −rel_tol·m00.
bool is_physically_realizable(const MuellerMatrix& m, double rel_tol = 1e-9);

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

/// The nominal angle in hundredths of a degree, rounded: equal keys ⇔ the same angle.
inline long polarizer_angle_key(double angle_deg) { return std::lround(angle_deg * 100.0); }

/// Whether two nominal angles name the same polarizer position (equal keys).
inline bool same_polarizer_angle(double a_deg, double b_deg) {
    return polarizer_angle_key(a_deg) == polarizer_angle_key(b_deg);
}

/// The angle of a key, degrees.
inline double polarizer_angle_deg(long key) { return static_cast<double>(key) / 100.0; }

/// The angle as it appears in channel names: shortest form of its key's angle with '.' → 'p'
/// ("0", "45", "22p5", "-10"), so 45 and 45.0 give the same name.
std::string polarizer_angle_tag(double angle_deg);

/// `angle_deg` wrapped to [0, 360).
inline double wrap_degrees(double angle_deg) {
    double a = std::fmod(angle_deg, 360.0);
    if (a < 0.0) a += 360.0;
    return a >= 360.0 ? 0.0 : a;
}

/// Signed smallest difference a − b in degrees, in [−180, 180) (how far a stage is from a request).
inline double angle_difference_deg(double a_deg, double b_deg) {
    return wrap_degrees(a_deg - b_deg + 180.0) - 180.0;
}

}  // namespace tirpol
