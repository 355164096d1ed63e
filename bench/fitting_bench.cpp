// Fitting benchmarks: one material (one band, 20 angles) from 16 starts with automatic derivatives
// (Jets through the quadrature) and, in the same run, with central numerical derivatives
// (ceres::NumericDiffCostFunction) — the ratio is the figure to read; residual+Jacobian evaluations
// per second for both. And the fit through the renderer: 3 views of panels_night at 160×120, 8 spp,
// n and σ of the flat black paint from eq 17's first guess, on 2 render threads (wall time).

#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "tirpol/core/geometry.h"
#include "tirpol/core/source_tree.h"
#include "tirpol/fitting/microfacet_fit.h"
#include "tirpol/fitting/render_fit.h"
#include "tirpol/simulation/renderer.h"

namespace {

using namespace tirpol;
using namespace tirpol::fitting;

// The flat black paint of config/materials (n 1.6, k 0.1, σ 0.35) with a small diffuse term,
// 20 angles 0–85.5°, noise of a good measurement.
EmissivityDataset paint_measurement() {
    const materials::ShellTargetParameters<double> truth{
        1.6, 0.1, 0.35, 1.0, deg_to_rad(90.0), deg_to_rad(1e6), 0.005, 0.0};
    std::mt19937_64 rng(20);
    std::normal_distribution<double> normal;
    EmissivityDataset d{"bench", 10.0, {}};
    for (int i = 0; i < 20; ++i) {
        const double a = 4.5 * i;
        const auto [s0, s1] = EmissivityQuadrature(deg_to_rad(a)).emissivity(truth);
        d.samples.push_back(
            {a, s0 + 0.004 * normal(rng), 0.004, s1 + 0.002 * normal(rng), 0.002, ""});
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

void BM_Fit16Starts_AutoDiff(benchmark::State& state) {
    fit_sixteen_starts(state, Derivatives::Automatic);
}
void BM_Fit16Starts_NumericDiff(benchmark::State& state) {
    fit_sixteen_starts(state, Derivatives::Numeric);
}

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

void BM_ResidualJacobian_AutoDiff(benchmark::State& state) {
    evaluations(state, Derivatives::Automatic);
}
void BM_ResidualJacobian_NumericDiff(benchmark::State& state) {
    evaluations(state, Derivatives::Numeric);
}

// The twin's three camera positions; the measurement is the truth rendered with its own seed, its σ
// the render's own; the emissivity tables of the unchanged materials come from the disk cache (as
// in use).
void BM_RenderFit_3Views_160x120_2Params(benchmark::State& state) {
    simulation::Scene scene = simulation::load_scene(find_config("scenes/panels_night.yaml"));
    scene.camera = scene.camera.resized(160, 120);
    scene.sampling.samples_per_pixel = 8;
    const Vec3 at(0.0, 0.0, 1.1);
    std::size_t panel = 0;
    for (std::size_t i = 0; i < scene.objects.size(); ++i)
        if (scene.objects[i].name == "panel_flat_black_paint") panel = i;
    std::vector<RenderFitView> views;
    for (const Vec3& position :
         {Vec3(0.0, -6.0, 1.6), Vec3(0.0, -5.0, 3.4), Vec3(0.0, -3.8, 4.6)}) {
        simulation::Scene s = scene;
        s.camera = simulation::PinholeCamera(
            scene.camera.width(), scene.camera.height(), scene.camera.intrinsics(), position,
            simulation::PinholeCamera::look_at(position, at, Vec3(0.0, 0.0, 1.0)));
        s.sampling.seed = 1000 + views.size();
        Image measured = simulation::render(s);
        for (const char* k : {"S0", "S1", "S2"}) {
            std::vector<float> sd = measured.channel(std::string(k) + "_var");
            for (float& v : sd) v = std::sqrt(v);
            measured.set_channel(std::string(k) + "_std", std::move(sd));
        }
        RenderFitRegion region = object_region(measured, panel, "flat_black_paint");
        views.push_back({"view", s.camera, std::move(measured), {std::move(region)}});
    }
    RenderFitOptions o;
    o.parameters = {{"flat_black_paint", MicrofacetParameter::n, 1.2, 2.5, 1.53, {}},
                    {"flat_black_paint", MicrofacetParameter::sigma, 0.05, 1.0, 0.29, {}}};
    o.seed = 7;
    o.threads = 2;
    RenderFitSummary r;
    for (auto _ : state) r = fit_through_renderer(scene, views, o);
    state.counters["renders"] = r.renders;
    state.counters["reduced_chi2"] = r.reduced_chi2;
    state.counters["n"] = r.parameters[0].value;
    state.counters["sigma"] = r.parameters[1].value;
}

}  // namespace

BENCHMARK(BM_RenderFit_3Views_160x120_2Params)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();
BENCHMARK(BM_Fit16Starts_AutoDiff)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(BM_Fit16Starts_NumericDiff)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(BM_ResidualJacobian_AutoDiff)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ResidualJacobian_NumericDiff)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
