#pragma once
// The Ceres residual of one measured emissivity sample (private to tirpol::fitting).

#include <ceres/ceres.h>

#include <memory>

#include "tirpol/core/geometry.h"
#include "tirpol/fitting/microfacet_fit.h"

namespace tirpol::fitting::detail {

/// r = ((ε_S0,model − ε_S0)/σ_S0, (ε_S1,model − ε_S1)/σ_S1) as a function of the eight one-value
/// parameter blocks n, k, σ, bias, τ°, Ω°, ρ_D, ρ_V (microfacet_fit.h order).
struct EmissivityResidual {
    const EmissivityQuadrature* quadrature;
    EmissivitySample sample;

    template <typename T>
    bool operator()(const T* n, const T* k, const T* sigma, const T* bias, const T* tau_deg,
                    const T* omega_deg, const T* rho_d, const T* rho_v, T* residual) const {
        const materials::ShellTargetParameters<T> p = model_parameters_from_fit_order<T>(
            {n[0], k[0], sigma[0], bias[0], tau_deg[0], omega_deg[0], rho_d[0], rho_v[0]});
        const auto [s0, s1] = quadrature->emissivity(p);
        residual[0] = (s0 - T(sample.eps_s0)) * T(1.0 / sample.eps_s0_std);
        residual[1] = (s1 - T(sample.eps_s1)) * T(1.0 / sample.eps_s1_std);
        return true;
    }

    /// The form DynamicAutoDiffCostFunction calls: one pointer per parameter block.
    template <typename T>
    bool operator()(T const* const* p, T* residual) const {
        return (*this)(p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], residual);
    }
};

/// Jet width of the automatic derivatives. DynamicAutoDiffCostFunction seeds derivatives only for
/// the blocks Ceres asks a Jacobian for — never the constant (fixed) ones — in passes of this many,
/// so the default fit (4 free parameters) costs one pass with Jet<double, 4> instead of a
/// Jet<double, 8> that a fixed-size AutoDiffCostFunction over the eight blocks would carry for
/// every parameter.
inline constexpr int kJetStride = 4;

/// The residual as an automatic- or numeric-derivative cost function.
inline std::unique_ptr<ceres::CostFunction> make_cost_function(const EmissivityResidual& residual,
                                                               Derivatives derivatives) {
    if (derivatives == Derivatives::Numeric)
        return std::make_unique<ceres::NumericDiffCostFunction<EmissivityResidual, ceres::CENTRAL,
                                                               2, 1, 1, 1, 1, 1, 1, 1, 1>>(
            new EmissivityResidual(residual));
    auto cost =
        std::make_unique<ceres::DynamicAutoDiffCostFunction<EmissivityResidual, kJetStride>>(
            new EmissivityResidual(residual));
    for (std::size_t i = 0; i < kMicrofacetParameterCount; ++i) cost->AddParameterBlock(1);
    cost->SetNumResiduals(2);
    return cost;
}

}  // namespace tirpol::fitting::detail
