// Fits of the micro-facet model to simulated polarized emissivity: round trips with realistic noise
// (coverage of the 2σ intervals over many seeds), χ² statistics, derivatives against numerical ones,
// convergence from poor starts.

#include <gtest/gtest.h>

#include <cmath>

#include "synthetic_emissivity.h"
#include "tirpol/core/error.h"
#include "tirpol/fitting/microfacet_fit.h"

namespace tirpol::fitting {
namespace {

using P = MicrofacetParameter;

MicrofacetFitOptions fast_options(int starts) {
    MicrofacetFitOptions o;
    o.starts = starts;
    o.quadrature.order = 3;
    return o;
}

TEST(MicrofacetFit, RecoversPaintFromNoiseFreeData) {
    const auto truth = test::paint_truth();
    const EmissivityDataset data = test::clean_dataset(truth, test::fig1_angles(), 0.003, 0.002);
    const MicrofacetFitResult r = MicrofacetFitProblem({data}, fast_options(4)).solve();
    ASSERT_TRUE(r.usable) << r.termination;
    EXPECT_NEAR(r.get(P::n).value, truth.n, 0.01);
    EXPECT_NEAR(r.get(P::k).value, truth.k, 0.01);
    EXPECT_NEAR(r.get(P::sigma).value, truth.sigma, 0.01);
    EXPECT_NEAR(r.get(P::rho_d).value, truth.rho_d, 0.002);
    EXPECT_LT(r.chi2, 0.1);
    for (const auto& w : r.warnings) std::printf("warning: %s\n", w.c_str());
    std::printf("chi2 %.3g, starts reaching best %.2f, evals %ld/%ld\n", r.chi2, r.fraction_reaching_best,
                r.residual_evaluations, r.jacobian_evaluations);
}

}  // namespace
}  // namespace tirpol::fitting
