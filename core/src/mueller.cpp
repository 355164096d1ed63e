#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>

#include "tirpol/core/error.h"
#include "tirpol/core/stokes.h"

namespace tirpol {

MuellerMatrix frame_rotation(double angle_rad) {
    const double c = std::cos(2.0 * angle_rad), s = std::sin(2.0 * angle_rad);
    MuellerMatrix m = MuellerMatrix::Identity();
    m(1, 1) = c;
    m(1, 2) = s;
    m(2, 1) = -s;
    m(2, 2) = c;
    return m;
}

MuellerMatrix rotate_element(const MuellerMatrix& m, double angle_rad) {
    return frame_rotation(-angle_rad) * m * frame_rotation(angle_rad);
}

MuellerMatrix linear_diattenuator(double axis_rad, double t_max, double t_min) {
    if (!(t_max >= 0.0 && t_min >= 0.0 && t_max <= 1.0 && t_min <= 1.0))
        fail("linear_diattenuator: transmittances must lie in [0, 1], got t_max={} t_min={}", t_max,
             t_min);
    const double a = 0.5 * (t_max + t_min), b = 0.5 * (t_max - t_min), c = std::sqrt(t_max * t_min);
    MuellerMatrix m;
    m << a, b, 0, 0,  //
        b, a, 0, 0,   //
        0, 0, c, 0,   //
        0, 0, 0, c;
    return rotate_element(m, axis_rad);
}

MuellerMatrix linear_polarizer(double axis_rad) { return linear_diattenuator(axis_rad, 1.0, 0.0); }

MuellerMatrix polarizer_with_extinction(double axis_rad, double transmission,
                                        double extinction_ratio) {
    if (!(extinction_ratio >= 1.0))
        fail("polarizer extinction ratio must be ≥ 1 (t_max/t_min), got {}", extinction_ratio);
    return linear_diattenuator(axis_rad, transmission, transmission / extinction_ratio);
}

MuellerMatrix linear_retarder(double fast_axis_rad, double retardance_rad) {
    const double c = std::cos(retardance_rad), s = std::sin(retardance_rad);
    MuellerMatrix m;
    m << 1, 0, 0, 0,  //
        0, 1, 0, 0,   //
        0, 0, c, s,   //
        0, 0, -s, c;
    return rotate_element(m, fast_axis_rad);
}

MuellerMatrix depolarizer(double retained_fraction) {
    MuellerMatrix m = MuellerMatrix::Identity() * retained_fraction;
    m(0, 0) = 1.0;
    return m;
}

namespace {
using C = std::complex<double>;
const std::array<Eigen::Matrix2cd, 4>& pauli() {
    static const std::array<Eigen::Matrix2cd, 4> p = [] {
        std::array<Eigen::Matrix2cd, 4> a;
        a[0] << 1, 0, 0, 1;
        a[1] << 1, 0, 0, -1;
        a[2] << 0, 1, 1, 0;
        a[3] << 0, C(0, -1), C(0, 1), 0;
        return a;
    }();
    return p;
}
}  // namespace

MuellerMatrix mueller_from_jones(const JonesMatrix& j) {
    const auto& s = pauli();
    MuellerMatrix m;
    const JonesMatrix jh = j.adjoint();
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
            m(a, b) =
                0.5 * (s[static_cast<std::size_t>(a)] * j * s[static_cast<std::size_t>(b)] * jh)
                          .trace()
                          .real();
    return m;
}

Eigen::Matrix4cd cloude_coherency(const MuellerMatrix& m) {
    const auto& s = pauli();
    Eigen::Matrix4cd h = Eigen::Matrix4cd::Zero();
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) {
            const Eigen::Matrix2cd& sa = s[static_cast<std::size_t>(a)];
            const Eigen::Matrix2cd sb = s[static_cast<std::size_t>(b)].conjugate();
            Eigen::Matrix4cd kron;
            for (int i = 0; i < 2; ++i)
                for (int k = 0; k < 2; ++k) kron.block<2, 2>(2 * i, 2 * k) = sa(i, k) * sb;
            h += m(a, b) * kron;
        }
    return 0.25 * h;
}

bool is_physically_realizable(const MuellerMatrix& m, double rel_tol) {
    if (!m.allFinite() || m(0, 0) < 0.0) return false;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix4cd> solver(cloude_coherency(m),
                                                           Eigen::EigenvaluesOnly);
    return solver.eigenvalues().minCoeff() >= -rel_tol * std::max(m(0, 0), 1e-300);
}

}  // namespace tirpol
