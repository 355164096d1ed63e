#pragma once
/// \file mueller.h
/// Mueller matrices of standard elements, in the Stokes convention of stokes.h. Angles are the
/// element's axis angle measured counter-clockwise from the frame's reference axis, looking into
/// the beam (Collett, "Field Guide to Polarization", 2005, §§ "Mueller matrices"; Chipman, Lam &
/// Young, "Polarized Light and Optical Systems", 2018, ch. 6).

#include <Eigen/Core>
#include <complex>

#include "tirpol/core/stokes.h"

namespace tirpol {

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

}  // namespace tirpol
