#pragma once
// The Ceres residual of one measured emissivity sample (private to tirpol::fitting).

#include <ceres/ceres.h>

#include <memory>

#include "tirpol/core/geometry.h"
#include "tirpol/fitting/emissivity_quadrature.h"
#include "tirpol/fitting/microfacet_fit.h"

namespace tirpol::fitting::detail {

/// r = ((ε_S0,model − ε_S0)/σ_S0, (ε_S1,model − ε_S1)/σ_S1) as a function of the eight one-value
/// parameter blocks n, k, σ, bias, τ°, Ω°, ρ_D, ρ_V (microfacet_fit.h order).
struct EmissivityResidual {
    const EmissivityQuadrature* quadrature;
    EmissivitySample sample;

    template <typename T>
    bool operator()(const T* n, const T* k, const T* sigma, const T* bias, const T* tau_deg, const T* omega_deg,
                    const T* rho_d, const T* rho_v, T* residual) const {
        const materials::ShellTargetParameters<T> p{n[0],
                                                    k[0],
                                                    sigma[0],
                                                    bias[0],
                                                    tau_deg[0] * T(deg_to_rad(1.0)),
                                                    omega_deg[0] * T(deg_to_rad(1.0)),
                                                    rho_d[0],
                                                    rho_v[0]};
        const auto [s0, s1] = quadrature->emissivity(p);
        residual[0] = (s0 - T(sample.e_s0)) * T(1.0 / sample.e_s0_sigma);
        residual[1] = (s1 - T(sample.e_s1)) * T(1.0 / sample.e_s1_sigma);
        return true;
    }
};

/// The residual as an automatic- or numeric-derivative cost function.
inline std::unique_ptr<ceres::CostFunction> make_cost_function(const EmissivityResidual& residual,
                                                               Derivatives derivatives) {
    if (derivatives == Derivatives::Numeric)
        return std::make_unique<ceres::NumericDiffCostFunction<EmissivityResidual, ceres::CENTRAL, 2, 1, 1, 1, 1, 1,
                                                               1, 1, 1>>(new EmissivityResidual(residual));
    return std::make_unique<ceres::AutoDiffCostFunction<EmissivityResidual, 2, 1, 1, 1, 1, 1, 1, 1, 1>>(
        new EmissivityResidual(residual));
}

}  // namespace tirpol::fitting::detail
