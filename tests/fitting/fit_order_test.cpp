// The fit's parameter order (MicrofacetParameter, τ and Ω in degrees) and the model's parameters
// (τ, Ω in radians) convert in one place, both ways, without loss beyond the degree↔radian
// rounding.

#include <gtest/gtest.h>

#include "tirpol/fitting/microfacet_fit.h"

namespace tirpol::fitting {
namespace {

TEST(FitOrder, ModelParametersRoundTripThroughFitOrder) {
    const materials::ShellTargetParameters<double> p{
        1.62, 0.07, 0.31, 0.9, deg_to_rad(20.0), deg_to_rad(55.0), 0.012, 0.003};
    const auto values = fit_order_values(p);
    using P = MicrofacetParameter;
    EXPECT_EQ(values[static_cast<std::size_t>(P::n)], 1.62);
    EXPECT_EQ(values[static_cast<std::size_t>(P::sigma)], 0.31);
    EXPECT_NEAR(values[static_cast<std::size_t>(P::tau_deg)], 20.0, 1e-12);
    EXPECT_NEAR(values[static_cast<std::size_t>(P::omega_deg)], 55.0, 1e-12);
    EXPECT_EQ(values[static_cast<std::size_t>(P::rho_v)], 0.003);
    const auto back = model_parameters_from_fit_order(values);
    EXPECT_EQ(back.n, p.n);
    EXPECT_EQ(back.k, p.k);
    EXPECT_EQ(back.bias, p.bias);
    EXPECT_DOUBLE_EQ(back.tau_rad, p.tau_rad);
    EXPECT_DOUBLE_EQ(back.omega_rad, p.omega_rad);
    EXPECT_EQ(back.rho_d, p.rho_d);
}

}  // namespace
}  // namespace tirpol::fitting
