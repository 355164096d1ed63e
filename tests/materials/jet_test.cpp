// The micro-facet formulas are templates so that tirpol::fitting can differentiate them with
// ceres::Jet (header-only use here; DEPENDENCIES.md: std::complex<Jet> is not supported, hence
// TinyComplex). Automatic derivatives must equal central finite differences and stay finite at the
// degenerate normal/collinear geometry.

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>

#include "tirpol/materials/microfacet.h"

namespace tirpol::materials {
namespace {

using Jet = ceres::Jet<double, 8>;

ShellTargetParameters<double> base() { return {1.6, 0.1, 0.3, 0.9, 0.3, 0.9, 0.01, 0.02}; }

double& field(ShellTargetParameters<double>& p, int i) {
    double* fields[8] = {&p.n,       &p.k,         &p.sigma, &p.bias,
                         &p.tau_rad, &p.omega_rad, &p.rho_d, &p.rho_v};
    return *fields[i];
}

ShellTargetParameters<Jet> to_jet(ShellTargetParameters<double> p) {
    ShellTargetParameters<Jet> j;
    Jet* fields[8] = {&j.n, &j.k, &j.sigma, &j.bias, &j.tau_rad, &j.omega_rad, &j.rho_d, &j.rho_v};
    for (int i = 0; i < 8; ++i) *fields[i] = Jet(field(p, i), i);
    return j;
}

TEST(JetDifferentiation, DerivativesMatchFiniteDifferences) {
    for (const auto& [wi, wo] : {std::pair{Vec3(0.3, 0.2, 0.9), Vec3(-0.5, 0.1, 0.7)},
                                 std::pair{Vec3(0.8, 0.0, 0.2), Vec3(-0.7, -0.3, 0.3)}}) {
        const MicrofacetGeometry g = microfacet_geometry(wi.normalized(), wo.normalized());
        const Mueller4<Jet> m = shell_target_mueller(to_jet(base()), g);
        for (int i = 0; i < 8; ++i) {
            ShellTargetParameters<double> plus = base(), minus = base();
            const double h = 1e-6 * std::max(1.0, std::abs(field(plus, i)));
            field(plus, i) += h;
            field(minus, i) -= h;
            const Mueller4<double> mp = shell_target_mueller(plus, g),
                                   mm = shell_target_mueller(minus, g);
            for (std::size_t r = 0; r < 4; ++r)
                for (std::size_t c = 0; c < 4; ++c) {
                    const double fd = (mp[r][c] - mm[r][c]) / (2.0 * h);
                    EXPECT_NEAR(m[r][c].v[i], fd, 1e-6 * std::max(1.0, std::abs(fd)))
                        << "param " << i << " m" << r << c;
                }
        }
    }
}

TEST(JetDifferentiation, FiniteAtNormalAndCollinearGeometry) {
    for (const auto& [wi, wo] : {std::pair<Vec3, Vec3>{Vec3::UnitZ(), Vec3::UnitZ()},
                                 std::pair<Vec3, Vec3>{Vec3(0.5, 0.5, 0.7).normalized(),
                                                       Vec3(0.5, 0.5, 0.7).normalized()}}) {
        const Mueller4<Jet> m = shell_target_mueller(to_jet(base()), microfacet_geometry(wi, wo));
        for (const auto& row : m)
            for (const Jet& x : row) {
                EXPECT_TRUE(std::isfinite(x.a));
                for (int i = 0; i < 8; ++i) EXPECT_TRUE(std::isfinite(x.v[i]));
            }
    }
}

}  // namespace
}  // namespace tirpol::materials
