// Materials throughput and accuracy: Mueller BRDF evaluations per second (reference in the same
// run: the closed-form Fresnel Mueller matrix alone and a Lambertian), the time to build one
// material's emissivity table for the 8–14 µm band, per-hit table lookups, and the table's accuracy
// against a brute-force hemispherical integration computed in the same run (reported as counters),
// and the spread of the micro-facet sample weights (the reference for a cheaper proposal).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "lambertian.h"
#include "smooth_fresnel.h"
#include "tirpol/materials/emissivity.h"
#include "tirpol/materials/fresnel.h"
#include "tirpol/materials/material.h"
#include "tirpol/materials/microfacet.h"

namespace {
using namespace tirpol;
using namespace tirpol::materials;

MicrofacetBrdf flat_black_paint() {  // the values of config/materials/flat_black_paint.yaml
    MicrofacetParameters p;
    p.index = RefractiveIndexTable::constant({1.6, 0.1});
    p.sigma = 0.35;
    return MicrofacetBrdf(p);
}

std::vector<std::pair<Vec3, Vec3>> random_pairs(int n) {
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<std::pair<Vec3, Vec3>> out;
    auto dir = [&] {
        const double c = u(rng), p = 2.0 * kPi * u(rng), s = std::sqrt(1.0 - c * c);
        return Vec3(s * std::cos(p), s * std::sin(p), c);
    };
    for (int i = 0; i < n; ++i) out.emplace_back(dir(), dir());
    return out;
}

void BM_Reference_FresnelMueller(benchmark::State& state) {
    double c = 0.0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(fresnel_mueller({1.6, 0.1}, c));
        c = c < 1.0 ? c + 1e-4 : 0.0;
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Reference_FresnelMueller);

void BM_Reference_LambertianEval(benchmark::State& state) {
    const LambertianBrdf lambert(SpectralValue(0.05));
    const auto pairs = random_pairs(4096);
    std::size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(lambert.eval(pairs[i].first, pairs[i].second, 10.0));
        i = (i + 1) & 4095;
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Reference_LambertianEval);

void BM_MicrofacetEval(benchmark::State& state) {
    const MicrofacetBrdf paint = flat_black_paint();
    const auto pairs = random_pairs(4096);
    std::size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(paint.eval(pairs[i].first, pairs[i].second, 10.0));
        i = (i + 1) & 4095;
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_MicrofacetEval);

void BM_MicrofacetSample(benchmark::State& state) {
    const MicrofacetBrdf paint = flat_black_paint();
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const Vec3 wo = Vec3(0.5, 0.1, 0.8).normalized();
    for (auto _ : state) benchmark::DoNotOptimize(paint.sample(wo, 10.0, u(rng), u(rng)));
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_MicrofacetSample);

// The facet-normal draw alone (Smith's terms at wo included), the part of MicrofacetSample that
// inverts the visible-slope CDF.
void BM_VisibleNormalSample(benchmark::State& state) {
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const Vec3 wo = Vec3(0.5, 0.1, 0.8).normalized();
    for (auto _ : state) benchmark::DoNotOptimize(sample_visible_normal(wo, 0.35, u(rng), u(rng)));
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_VisibleNormalSample);

// The spread of the sample weight's S0 and S1 (first column: unpolarized light in) over 400 000
// samples per model and view, printed with its mean: a proposal cheaper than the visible normals
// must be judged by cost × variance, so this is the reference to compare a new one against. The
// means are the directional-hemispherical reflectance (Sampling tests check them against the
// emissivity quadrature); with only a specular lobe a constant weight would have spread 0.
void BM_MicrofacetWeightSpread(benchmark::State& state) {
    struct Model {
        const char* name;
        double n, k, sigma, rho_d, rho_v;
    };
    const Model models[] = {
        {"metal (12.1+69.2i, sigma 0.1)", 12.1, 69.2, 0.1, 0.0, 0.0},
        {"glossy paint (1.55+0.1i, 0.05, rho_d 0.004)", 1.55, 0.1, 0.05, 0.004, 0.0},
        {"flat paint (1.6+0.1i, 0.35)", 1.6, 0.1, 0.35, 0.0, 0.0},
        {"rough (1.6+0.05i, 0.3, rho_d 0.01, rho_v 0.02)", 1.6, 0.05, 0.3, 0.01, 0.02}};
    for (auto _ : state) {
        for (const Model& m : models) {
            MicrofacetParameters p;
            p.index = RefractiveIndexTable::constant({m.n, m.k});
            p.sigma = m.sigma;
            p.rho_d = m.rho_d;
            p.rho_v = m.rho_v;
            const MicrofacetBrdf brdf(p);
            for (double theta_deg : {5.0, 40.0, 70.0, 85.0, 89.0}) {
                std::mt19937_64 rng(23);
                std::uniform_real_distribution<double> u(0.0, 1.0);
                const double t = deg_to_rad(theta_deg);
                const Vec3 wo(std::sin(t), 0.0, std::cos(t));
                constexpr int kSamples = 400000;
                double s0 = 0.0, s00 = 0.0, s1 = 0.0, s11 = 0.0, largest = 0.0;
                for (int i = 0; i < kSamples; ++i) {
                    const BrdfSample smp = brdf.sample(wo, 10.0, u(rng), u(rng));
                    if (!(smp.pdf > 0.0)) continue;
                    const double w0 = smp.weight(0, 0), w1 = smp.weight(1, 0);
                    s0 += w0;
                    s00 += w0 * w0;
                    s1 += w1;
                    s11 += w1 * w1;
                    largest = std::max(largest, w0);
                }
                const double m0 = s0 / kSamples, m1 = s1 / kSamples;
                std::printf(
                    "%-48s %4.0f deg: S0 mean %.5f sd %.5f, S1 mean %+.5f sd %.5f, "
                    "largest S0 weight %.3f\n",
                    m.name, theta_deg, m0, std::sqrt(std::max(0.0, s00 / kSamples - m0 * m0)), m1,
                    std::sqrt(std::max(0.0, s11 / kSamples - m1 * m1)), largest);
            }
        }
    }
}
BENCHMARK(BM_MicrofacetWeightSpread)->Iterations(1)->Unit(benchmark::kSecond);

// One table for the 8–14 µm band (0.5 µm steps = 13 wavelengths, 65 angles; table build uses all
// cores). The paint's parameters are spectrally constant (one column is integrated, the others
// reuse it); water's index is tabulated (every column integrated, smooth Fresnel: exact, one sample
// each); a micro-facet model with a tabulated index is the worst case (every column integrated).
// Wall time ("Time") is the figure to read: the CPU column counts the calling thread only.
void BM_EmissivityTableBand_FlatBlackPaint(benchmark::State& state) {
    const MicrofacetBrdf paint = flat_black_paint();
    const auto wl = EmissivityTable::wavelengths_for_band(Band(8.0, 14.0));
    for (auto _ : state) benchmark::DoNotOptimize(EmissivityTable(paint, wl));
}
BENCHMARK(BM_EmissivityTableBand_FlatBlackPaint)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_EmissivityTableBand_SpectralMicrofacet(benchmark::State& state) {
    MicrofacetParameters p;
    p.index = RefractiveIndexTable({8.0, 14.0}, {1.5, 1.7}, {0.05, 0.2}, "bench");
    p.sigma = 0.2;
    p.rho_d = 0.01;
    const MicrofacetBrdf brdf(p);
    const auto wl = EmissivityTable::wavelengths_for_band(Band(8.0, 14.0));
    for (auto _ : state) benchmark::DoNotOptimize(EmissivityTable(brdf, wl));
    state.counters["wavelengths"] = static_cast<double>(wl.size());
}
BENCHMARK(BM_EmissivityTableBand_SpectralMicrofacet)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_EmissivityTableBand_Water(benchmark::State& state) {
    const SmoothFresnelBrdf water(
        RefractiveIndexTable({8.0, 10.0, 12.0, 14.0}, {1.291, 1.218, 1.111, 1.210},
                             {0.0343, 0.0508, 0.199, 0.370}, "Hale & Querry 1973"));
    const auto wl = EmissivityTable::wavelengths_for_band(Band(8.0, 14.0));
    for (auto _ : state) benchmark::DoNotOptimize(EmissivityTable(water, wl));
}
BENCHMARK(BM_EmissivityTableBand_Water)->Unit(benchmark::kMillisecond);

void BM_EmissivityTableLookup(benchmark::State& state) {
    const MicrofacetBrdf paint = flat_black_paint();
    const EmissivityTable table(paint, {10.0});
    double c = 0.0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(table.at(c, 0));
        c = c < 1.0 ? c + 1e-4 : 0.0;
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_EmissivityTableLookup);

void BM_EmissivityBandAverageLookup(benchmark::State& state) {
    const MicrofacetBrdf paint = flat_black_paint();
    const Band band(8.0, 14.0);
    const EmissivityTable table(paint, EmissivityTable::wavelengths_for_band(band));
    double c = 0.0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(table.band_average(c, band, 300.0));
        c = c < 1.0 ? c + 1e-4 : 0.0;
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_EmissivityBandAverageLookup);

void BM_EmissivityWeightedLookup(
    benchmark::State& state) {  // band weights precomputed once per (band, T)
    const MicrofacetBrdf paint = flat_black_paint();
    const Band band(8.0, 14.0);
    const EmissivityTable table(paint, EmissivityTable::wavelengths_for_band(band));
    const std::vector<double> weights = table.band_weights(band, 300.0);
    double c = 0.0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(table.at_weighted(c, weights));
        c = c < 1.0 ? c + 1e-4 : 0.0;
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_EmissivityWeightedLookup);

// Accuracy in the same run: the table (default quadrature) against a brute-force midpoint
// integration of eval over 600 × 1200 (θi, φi) cells at 0, 30, 60, 80, 85, 89 degrees. Counters:
// max |Δε_S0|, max |Δε_S1| over those angles; the timed part is the brute-force reference for one
// angle.
void BM_AccuracyVsBruteForce(benchmark::State& state) {
    const MicrofacetBrdf paint = flat_black_paint();
    const EmissivityTable table(paint, {10.0});
    auto brute = [&](double theta) {
        const Vec3 wo(std::sin(theta), 0.0, std::cos(theta));
        StokesVector sum = StokesVector::Zero();
        constexpr int nt = 600, np = 1200;
        const double dt = 0.5 * kPi / nt, dp = 2.0 * kPi / np;
        for (int i = 0; i < nt; ++i) {
            const double t = (i + 0.5) * dt;
            for (int j = 0; j < np; ++j) {
                const double p = (j + 0.5) * dp;
                const Vec3 wi(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
                sum += paint.eval(wi, wo, 10.0).col(0) * (std::cos(t) * std::sin(t) * dt * dp);
            }
        }
        return StokesVector(unpolarized(1.0) - sum);
    };
    double e0 = 0.0, e1 = 0.0;
    for (auto _ : state) {
        e0 = e1 = 0.0;
        for (double deg : {0.0, 30.0, 60.0, 80.0, 85.0, 89.0}) {
            const double t = deg_to_rad(deg);
            const StokesVector d = table.at(std::cos(t), 0) - brute(t);
            e0 = std::max(e0, std::abs(d(0)));
            e1 = std::max(e1, std::abs(d(1)));
        }
    }
    state.counters["max_abs_err_e_s0"] = e0;
    state.counters["max_abs_err_e_s1"] = e1;
}
BENCHMARK(BM_AccuracyVsBruteForce)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
