// Fitting benchmarks: one material (one band, 20 angles) from 16 starts with automatic derivatives
// (Jets through the quadrature) and, in the same run, with central numerical derivatives
// (ceres::NumericDiffCostFunction) — the ratio is the figure to read; residual+Jacobian evaluations
// per second for both.

#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "tirpol/core/geometry.h"
#include "tirpol/fitting/microfacet_fit.h"

namespace {

using namespace tirpol;
using namespace tirpol::fitting;

// The flat black paint of config/materials (n 1.6, k 0.1, σ 0.35) with a small diffuse term,
// 20 angles 0–85.5°, noise of a good measurement.
EmissivityDataset paint_measurement() {
    const materials::ShellTargetParameters<double> truth{1.6, 0.1, 0.35, 1.0, deg_to_rad(90.0), deg_to_rad(1e6),
                                                         0.005, 0.0};
    std::mt19937_64 rng(20);
    std::normal_distribution<double> normal;
    EmissivityDataset d{"bench", 10.0, {}};
    for (int i = 0; i < 20; ++i) {
        const double a = 4.5 * i;
        const auto [s0, s1] = EmissivityQuadrature(deg_to_rad(a)).emissivity(truth);
        d.samples.push_back({a, s0 + 0.004 * normal(rng), 0.004, s1 + 0.002 * normal(rng), 0.002, ""});
    }
    return d;
}

MicrofacetFitOptions options(Derivatives derivatives) {
    MicrofacetFitOptions o;
    o.starts = 16;
    o.derivatives = derivatives;
    return o;
}

void fit_sixteen_starts(benchmark::State& state, Derivatives derivatives) {
    const MicrofacetFitProblem problem({paint_measurement()}, options(derivatives));
    long jacobians = 0;
    double fraction = 0.0;
    for (auto _ : state) {
        const MicrofacetFitResult r = problem.solve();
        jacobians += r.jacobian_evaluations;
        fraction = r.fraction_reaching_best;
        benchmark::DoNotOptimize(r.chi2);
    }
    state.counters["jacobian_evals_per_fit"] =
        benchmark::Counter(static_cast<double>(jacobians), benchmark::Counter::kAvgIterations);
    state.counters["starts_reaching_best"] = fraction;
}

void BM_Fit16Starts_AutoDiff(benchmark::State& state) { fit_sixteen_starts(state, Derivatives::Automatic); }
void BM_Fit16Starts_NumericDiff(benchmark::State& state) { fit_sixteen_starts(state, Derivatives::Numeric); }

void evaluations(benchmark::State& state, Derivatives derivatives) {
    const MicrofacetFitProblem problem({paint_measurement()}, options(derivatives));
    const std::vector<double> values = problem.initial_values();
    std::vector<double> residuals, jacobian;
    for (auto _ : state) {
        problem.evaluate(values, &residuals, &jacobian);
        benchmark::DoNotOptimize(jacobian.data());
    }
    state.counters["residual_jacobian_evals_per_s"] =
        benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_ResidualJacobian_AutoDiff(benchmark::State& state) { evaluations(state, Derivatives::Automatic); }
void BM_ResidualJacobian_NumericDiff(benchmark::State& state) { evaluations(state, Derivatives::Numeric); }

}  // namespace

BENCHMARK(BM_Fit16Starts_AutoDiff)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(BM_Fit16Starts_NumericDiff)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(BM_ResidualJacobian_AutoDiff)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ResidualJacobian_NumericDiff)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
