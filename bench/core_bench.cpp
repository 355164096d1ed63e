// Core throughput: Planck, band radiance, brightness temperature, Stokes frame changes, EXR writes.
// Each group carries its own reference (a single Planck evaluation, a memcpy) so figures read as
// ratios.

#include <benchmark/benchmark.h>

#include <cstring>
#include <filesystem>
#include <random>

#include "tirpol/core/exr_io.h"
#include "tirpol/core/radiometry.h"
#include "tirpol/core/stokes.h"

namespace {
using namespace tirpol;

void BM_PlanckSpectral(benchmark::State& state) {
    double t = 250.0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(planck_radiance(10.0, t));
        t = t < 350.0 ? t + 0.01 : 250.0;
    }
}
BENCHMARK(BM_PlanckSpectral);

void BM_BandRadiance8to14(benchmark::State& state) {
    const Band band(8.0, 14.0);
    double t = 250.0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(band.radiance(t));
        t = t < 350.0 ? t + 0.01 : 250.0;
    }
    state.counters["nodes"] = static_cast<double>(band.nodes().size());
}
BENCHMARK(BM_BandRadiance8to14);

void BM_BrightnessTemperature8to14(benchmark::State& state) {
    const Band band(8.0, 14.0);
    double l = 30.0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(band.brightness_temperature(l));
        l = l < 80.0 ? l + 0.01 : 30.0;
    }
}
BENCHMARK(BM_BrightnessTemperature8to14);

void BM_StokesChangeFrame(benchmark::State& state) {
    std::mt19937 rng(1);
    std::normal_distribution<double> n;
    std::vector<Vec3> dirs(1024);
    for (auto& d : dirs) d = Vec3(n(rng), n(rng), n(rng)).normalized();
    const StokesVector s(1.0, 0.1, 0.05, 0.0);
    std::size_t i = 0;
    for (auto _ : state) {
        const Vec3& k = dirs[i++ & 1023];
        benchmark::DoNotOptimize(
            change_frame(s, world_frame(k), surface_frame(k, dirs[(i * 7) & 1023])));
    }
}
BENCHMARK(BM_StokesChangeFrame);

void BM_MemcpyReference640x512x6(benchmark::State& state) {
    std::vector<float> a(640 * 512 * 6, 1.0f), b(a.size());
    for (auto _ : state) {
        std::memcpy(b.data(), a.data(), a.size() * sizeof(float));
        benchmark::ClobberMemory();
    }
    state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * a.size() * sizeof(float)));
}
BENCHMARK(BM_MemcpyReference640x512x6);

void BM_WriteStokesExr640x512(benchmark::State& state) {
    Image img(640, 512);
    std::mt19937 rng(2);
    std::normal_distribution<float> n(50.0f, 1.0f);
    for (const char* c : {"S0", "S1", "S2", "S3", "DoLP", "AoP"})
        for (auto& v : img.add_channel(c)) v = n(rng);
    const auto path = std::filesystem::temp_directory_path() / "tirpol-bench.exr";
    for (auto _ : state) write_exr(path, img);
    std::filesystem::remove(path);
    state.SetBytesProcessed(
        static_cast<int64_t>(state.iterations() * img.pixel_count() * 6 * sizeof(float)));
}
BENCHMARK(BM_WriteStokesExr640x512)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
