// Microgrid (division-of-focal-plane) frames of 640×512 (an LWIR microgrid bolometer's size):
// demosaicing alone and demosaicing + Stokes reduction (S0 S1 S2 DoLP AoP) per method (the single
// pass from float and from 16-bit frames, and the two-step path it replaced), and the
// per-super-pixel reduction with a per-pixel analyzer calibration, on one core. items_per_second =
// frames/s.

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <random>

#include "tirpol/calibration/microgrid_session.h"
#include "tirpol/calibration/microgrid_stokes.h"

namespace {

using namespace tirpol;
using namespace tirpol::calibration;

constexpr int kW = 640, kH = 512;
constexpr std::size_t kN = static_cast<std::size_t>(kW) * kH;

/// A textured, partially polarized scene with 16-bit-like counts and noise.
const std::vector<float>& frame() {
    static const std::vector<float> mosaic = [] {
        std::vector<float> s0(kN), s1(kN), s2(kN);
        std::mt19937 rng(5);
        std::normal_distribution<float> noise(0.0f, 20.0f);
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const std::size_t i =
                    static_cast<std::size_t>(y) * kW + static_cast<std::size_t>(x);
                s0[i] = 20000.0f + 5000.0f * std::sin(0.05f * static_cast<float>(x)) +
                        (x > kW / 2 ? 8000.0f : 0.0f) + noise(rng);
                s1[i] = 0.1f * s0[i] * std::cos(0.02f * static_cast<float>(y));
                s2[i] = 0.05f * s0[i];
            }
        return microgrid_from_stokes(s0, s1, s2, kW, kH, MicrogridPattern::sony_imx250mzr());
    }();
    return mosaic;
}

void BM_Demosaic(benchmark::State& state) {
    const auto method = static_cast<DemosaicMethod>(state.range(0));
    const MicrogridPattern sony = MicrogridPattern::sony_imx250mzr();
    for (auto _ : state)
        benchmark::DoNotOptimize(demosaic_microgrid(frame(), kW, kH, sony, method));
    state.SetItemsProcessed(state.iterations());
    state.SetLabel(std::string(demosaic_method_name(method)));
}

void BM_DemosaicAndReduce(benchmark::State& state) {
    MicrogridReductionOptions options;
    options.method = static_cast<DemosaicMethod>(state.range(0));
    const MicrogridPattern sony = MicrogridPattern::sony_imx250mzr();
    for (auto _ : state) benchmark::DoNotOptimize(reduce_microgrid(frame(), kW, kH, sony, options));
    state.SetItemsProcessed(state.iterations());
    state.SetLabel(std::string(demosaic_method_name(options.method)));
}

/// An ideal-analyzer per-pixel calibration of the camera (the cost does not depend on the values).
MicrogridPixelCalibration ideal_pixel_calibration() {
    MicrogridPixelCalibration cal;
    cal.width = kW;
    cal.height = kH;
    for (auto& plane : cal.analysis) plane.assign(kN, 0.0f);
    cal.background.assign(kN, 0.0f);
    const MicrogridPattern sony = MicrogridPattern::sony_imx250mzr();
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * kW + static_cast<std::size_t>(x);
            const double two_theta = 2.0 * sony.angle_at_pixel_deg(x, y) * 3.14159265358979 / 180.0;
            cal.analysis[0][i] = 0.5f;
            cal.analysis[1][i] = static_cast<float>(0.5 * std::cos(two_theta));
            cal.analysis[2][i] = static_cast<float>(0.5 * std::sin(two_theta));
        }
    return cal;
}

/// One call per frame: the per-cell matrices are made again every time.
void BM_PerPixelCalibratedReduce(benchmark::State& state) {
    const MicrogridPixelCalibration cal = ideal_pixel_calibration();
    for (auto _ : state) benchmark::DoNotOptimize(reduce_microgrid_per_pixel(frame(), cal));
    state.SetItemsProcessed(state.iterations());
}

/// The matrices made once (MicrogridPixelReducer), then frame after frame: a live view's case.
void BM_PerPixelPreparedReduce(benchmark::State& state) {
    const MicrogridPixelReducer reducer(ideal_pixel_calibration());
    for (auto _ : state) benchmark::DoNotOptimize(reducer.reduce(frame()));
    state.SetItemsProcessed(state.iterations());
}

/// A camera's 16-bit frame as it arrives (no float copy), bilinear, the single pass.
void BM_DemosaicAndReduce16Bit(benchmark::State& state) {
    static const std::vector<std::uint16_t> counts(frame().begin(), frame().end());
    MicrogridReductionOptions options;
    options.method = static_cast<DemosaicMethod>(state.range(0));
    const MicrogridPattern sony = MicrogridPattern::sony_imx250mzr();
    for (auto _ : state)
        benchmark::DoNotOptimize(
            reduce_microgrid(std::span<const std::uint16_t>(counts), kW, kH, sony, options));
    state.SetItemsProcessed(state.iterations());
    state.SetLabel(std::string(demosaic_method_name(options.method)));
}

/// The two-step path (demosaic_microgrid, then the general reduce_stokes) for comparison.
void BM_DemosaicThenReduceStokes(benchmark::State& state) {
    MicrogridReductionOptions options;
    options.method = static_cast<DemosaicMethod>(state.range(0));
    options.single_pass = false;
    const MicrogridPattern sony = MicrogridPattern::sony_imx250mzr();
    for (auto _ : state) benchmark::DoNotOptimize(reduce_microgrid(frame(), kW, kH, sony, options));
    state.SetItemsProcessed(state.iterations());
    state.SetLabel(std::string(demosaic_method_name(options.method)));
}

}  // namespace

BENCHMARK(BM_Demosaic)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DemosaicAndReduce)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DemosaicAndReduce16Bit)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DemosaicThenReduceStokes)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PerPixelCalibratedReduce)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PerPixelPreparedReduce)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
