#pragma once
// First-order uncertainties of S0, S1, S2, DoLP and AoP from a Stokes vector's covariance: one
// definition for reduce_stokes and the per-pixel microgrid reduction.

namespace tirpol::calibration::detail {

/// The upper triangle of Cov(S0, S1, S2).
struct StokesCovariance {
    double c00 = 0.0, c11 = 0.0, c22 = 0.0, c01 = 0.0, c02 = 0.0, c12 = 0.0;
};

struct StokesStd {
    float s0 = 0.0f, s1 = 0.0f, s2 = 0.0f;
    float dolp = 0.0f;  ///< NaN where S0 ≤ 0 or the vector is unpolarized
    float aop_deg = 0.0f;
};

/// σ of S0, S1, S2, and of DoLP = pl/S0 and AoP = ½·atan2(S2, S1) by σ² = gᵀ·Cov·g with g their
/// gradients at s (pl = √(S1² + S2²), passed as the caller has it, e.g. S0 after a projection
/// onto the cone). AoP's σ is capped at 180°/√12 ≈ 52°, the σ of an AoP uniform on [0°, 180°),
/// where DoLP ≈ noise and the linearisation diverges.
StokesStd stokes_std(const double s[3], double pl, const StokesCovariance& c);

}  // namespace tirpol::calibration::detail
