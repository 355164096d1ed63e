#pragma once
/// \file stokes.h
/// Stokes vectors S = (S0, S1, S2, S3) and the quantities derived from them. A Stokes vector is
/// always expressed in some StokesFrame (stokes_frame.h): S1 > 0 means polarized along the frame's
/// reference axis (polarizer angle 0°), S2 > 0 along +45° (counter-clockwise looking into the
/// beam), S3 > 0 right-circular in the observer's view. Units are those of S0 (radiance, counts,
/// ...).

#include <Eigen/Core>

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

}  // namespace tirpol
