// The cost of the sky registry at a path end: Sky::AtWavelength::spectral_radiance, which calls the
// registered SkyModel through a virtual function, against the same arithmetic behind the switch
// over sky kinds that the registry replaced (copied here as it was, an out-of-line function as it
// was). Instructions per call: run under callgrind (docs/architecture.md, "A sky type").

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "tirpol/core/radiometry.h"
#include "tirpol/simulation/scene.h"

namespace {

using tirpol::Vec3;
using tirpol::simulation::Sky;

constexpr double kWavelengthUm = 10.0, kAirTemperatureK = 283.0, kZenithEmissivity = 0.7;
constexpr int kDirections = 4096;
constexpr int kIterations = 2000;  // fixed, so that callgrind's count divides into calls

/// Directions over the upper hemisphere (and a few below the horizon), as path ends see them.
std::vector<Vec3> directions() {
    std::vector<Vec3> out;
    for (int i = 0; i < kDirections; ++i) {
        const double z = -0.05 + 1.05 * (i + 0.5) / kDirections, phi = 2.399963 * i;
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        out.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
    }
    return out;
}

/// The sky at one wavelength before the registry: a kind and the two precomputed numbers.
struct SwitchedSky {
    enum class Kind { Uniform, ClearSky } kind;
    double blackbody, log_zenith_transmittance;
};

[[gnu::noinline]] double switched_radiance(const SwitchedSky& sky, const Vec3& direction) {
    switch (sky.kind) {
        case SwitchedSky::Kind::ClearSky:
            if (direction.z() <= 1e-6) return sky.blackbody;
            return -std::expm1(sky.log_zenith_transmittance / direction.z()) * sky.blackbody;
        case SwitchedSky::Kind::Uniform:
            break;
    }
    return sky.blackbody;
}

Sky registered(bool clear) {
    return clear ? Sky::clear_sky(kAirTemperatureK, kZenithEmissivity)
                 : Sky::uniform(kAirTemperatureK);
}

void BM_SkyPathEndRegistered(benchmark::State& state) {
    const Sky sky = registered(state.range(0) != 0);
    const Sky::AtWavelength at = sky.at_wavelength(kWavelengthUm);
    const std::vector<Vec3> d = directions();
    for (auto _ : state) {
        double sum = 0.0;
        for (const Vec3& v : d) sum += at.spectral_radiance(v);
        benchmark::DoNotOptimize(sum);
    }
    state.SetItemsProcessed(state.iterations() * kDirections);
}

void BM_SkyPathEndSwitch(benchmark::State& state) {
    const bool clear = state.range(0) != 0;
    const SwitchedSky sky{clear ? SwitchedSky::Kind::ClearSky : SwitchedSky::Kind::Uniform,
                          tirpol::planck_radiance(kWavelengthUm, kAirTemperatureK),
                          std::log1p(-kZenithEmissivity)};
    const std::vector<Vec3> d = directions();
    for (auto _ : state) {
        double sum = 0.0;
        for (const Vec3& v : d) sum += switched_radiance(sky, v);
        benchmark::DoNotOptimize(sum);
    }
    state.SetItemsProcessed(state.iterations() * kDirections);
}

// Argument: 0 uniform sky, 1 clear sky.
BENCHMARK(BM_SkyPathEndRegistered)->Arg(0)->Arg(1)->Iterations(kIterations);
BENCHMARK(BM_SkyPathEndSwitch)->Arg(0)->Arg(1)->Iterations(kIterations);

}  // namespace

BENCHMARK_MAIN();
