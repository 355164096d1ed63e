// Cost of a 640×512 comparison report (registration, statistics, 34 PNGs, HTML, JSON, EXR) against
// a reference measured in the same run: writing just the 15 quicklook PNGs of the side-by-side
// panels at full resolution. Also the automatic (ECC) registration alone.

#include <benchmark/benchmark.h>

#include <filesystem>

#include "../tests/report/synthetic_pair.h"
#include "tirpol/core/quicklook.h"
#include "tirpol/report/comparison_report.h"

namespace {
using namespace tirpol;

const report::test::SyntheticPair& pair640() {
    static const report::test::SyntheticPair pair = [] {
        report::test::SyntheticPairOptions o;
        o.width = 640;
        o.height = 512;
        o.shift_x_px = 2.4;
        o.shift_y_px = -1.3;
        o.s1_bias = 0.1;
        return report::test::make_synthetic_pair(o);
    }();
    return pair;
}

std::filesystem::path scratch(const char* name) {
    auto dir = std::filesystem::temp_directory_path() / name;
    std::filesystem::create_directories(dir);
    return dir;
}

void BM_ReferenceWrite15QuicklookPngs640x512(benchmark::State& state) {
    const auto& p = pair640();
    const auto dir = scratch("tirpol-bench-quicklooks");
    for (auto _ : state)
        for (int k = 0; k < 5; ++k)
            for (const auto* image : {&p.measured, &p.simulated, &p.measured}) {
                const auto& name = image->channel_names()[static_cast<std::size_t>(k % 3) * 2];
                write_quicklook(
                    dir / (std::to_string(k) + name + ".png"), image->channel(name), 640, 512,
                    {default_colormap(name), std::nullopt, std::nullopt, name, "W/(m²·sr)", 1});
            }
    std::filesystem::remove_all(dir);
}
BENCHMARK(BM_ReferenceWrite15QuicklookPngs640x512)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_EccRegistration640x512(benchmark::State& state) {
    const auto& p = pair640();
    for (auto _ : state)
        benchmark::DoNotOptimize(
            report::register_images(p.measured, p.simulated, report::RegistrationMethod::Auto, {}));
}
BENCHMARK(BM_EccRegistration640x512)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_ComparisonReport640x512(benchmark::State& state) {
    const auto& p = pair640();
    const auto dir = scratch("tirpol-bench-report");
    report::CompareOptions options;
    for (auto _ : state)
        benchmark::DoNotOptimize(
            report::write_comparison_report(p.measured, p.simulated, options, dir));
    std::filesystem::remove_all(dir);
}
BENCHMARK(BM_ComparisonReport640x512)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
