// Reduction throughput of `tirpol reduce` on a 640×512 4-angle session held in memory, against a
// plain memory copy of the same input data measured in the same run (the memory-bandwidth limit).
// Figures: items_per_second = pixels/s; compare "bytes_per_second" of the copy with the reduction.

#include <benchmark/benchmark.h>

#include <cstring>
#include <random>

#include "synthetic_fpa_camera.h"
#include "tirpol/calibration/radiometric.h"
#include "tirpol/calibration/stokes_reduction.h"

namespace {

using namespace tirpol;
using namespace tirpol::calibration;

constexpr int kW = 640, kH = 512;
constexpr std::size_t kN = static_cast<std::size_t>(kW) * kH;
const std::vector<double> kAngles{0.0, 45.0, 90.0, 135.0};

struct Session {
    std::vector<AnalyzerImage> counts;  // raw counts per angle (signal) + counts σ of the mean
    RadiometricCalibration radiometric;
    WireGridCalibration grid;
    AnalyzerModel model = AnalyzerModel::non_ideal(kAngles, 100.0, 1.5, 0.8);
};

const Session& session() {
    static const Session instance = [] {
        Session s;
        std::mt19937 rng(1);
        std::normal_distribution<float> unit(0.0f, 1.0f);
        s.radiometric.width = kW;
        s.radiometric.height = kH;
        s.radiometric.band_lo_um = 8.0;
        s.radiometric.band_hi_um = 14.0;
        for (std::size_t i = 0; i < kN; ++i) {
            s.radiometric.gain.push_back(100.0f + unit(rng));
            s.radiometric.offset.push_back(5000.0f + 10.0f * unit(rng));
        }
        s.radiometric.bad.assign(kN, 0.0f);
        s.grid.width = kW;
        s.grid.height = kH;
        for (double a : kAngles) {
            s.grid.positions.push_back(
                {a, std::vector<float>(kN, 0.8f), std::vector<float>(kN, 3.0f), {}});
            AnalyzerImage im{a, {}, {}, "bench"};
            for (std::size_t i = 0; i < kN; ++i) {
                im.signal.push_back(5000.0f + 100.0f * (20.0f + 0.1f * unit(rng)));
                im.signal_std.push_back(1.5f);
            }
            s.counts.push_back(std::move(im));
        }
        return s;
    }();
    return instance;
}

// Reference: copy the same input planes (4 angles × signal and σ, float) once.
void BM_MemoryCopyOfInputs(benchmark::State& state) {
    const Session& s = session();
    std::vector<float> dst(kN * 8);
    for (auto _ : state) {
        for (std::size_t k = 0; k < 4; ++k) {
            std::memcpy(dst.data() + (2 * k) * kN, s.counts[k].signal.data(), kN * sizeof(float));
            std::memcpy(dst.data() + (2 * k + 1) * kN, s.counts[k].signal_std.data(),
                        kN * sizeof(float));
        }
        benchmark::DoNotOptimize(dst.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                            static_cast<std::int64_t>(kN));
    state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                            static_cast<std::int64_t>(kN * 8 * sizeof(float)));
}

// Stokes reduction with wire-grid correction and uncertainty propagation (S0..AoP + 5 σ channels).
void BM_ReduceStokesWithUncertainties(benchmark::State& state) {
    const Session& s = session();
    for (auto _ : state) {
        Image out = reduce_stokes(s.counts, kW, kH, s.model, &s.grid);
        benchmark::DoNotOptimize(out.channel("S1").data());
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                            static_cast<std::int64_t>(kN));
    state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                            static_cast<std::int64_t>(kN * 8 * sizeof(float)));
}

// The whole in-memory `reduce`: counts → radiance (with bad-pixel replacement) per angle, then
// Stokes.
void BM_CountsToStokes(benchmark::State& state) {
    const Session& s = session();
    for (auto _ : state) {
        std::vector<AnalyzerImage> radiance;
        for (const auto& im : s.counts)
            radiance.push_back({im.angle_deg, counts_to_radiance(s.radiometric, im.signal),
                                im.signal_std, im.source});
        Image out = reduce_stokes(radiance, kW, kH, s.model, &s.grid);
        benchmark::DoNotOptimize(out.channel("S1").data());
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                            static_cast<std::int64_t>(kN));
    state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                            static_cast<std::int64_t>(kN * 8 * sizeof(float)));
}

// Counts → radiance of the 4 angle images alone.
void BM_CountsToRadiance(benchmark::State& state) {
    const Session& s = session();
    for (auto _ : state)
        for (const auto& im : s.counts) {
            auto radiance = counts_to_radiance(s.radiometric, im.signal);
            benchmark::DoNotOptimize(radiance.data());
        }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                            static_cast<std::int64_t>(kN));
}

// FPA-temperature-dependent calibration: blackbody at 8 set-points × 3 camera
// temperatures on a 640×512 camera, the frames held in memory as `calibrate radiometric` holds
// them.
struct FpaCalibrationInputs {
    std::vector<BlackbodyFrame> frames;
    RadiometricCalibration fitted;
    BlackbodyFrame scene;
};

const FpaCalibrationInputs& fpa_inputs() {
    static const FpaCalibrationInputs instance = [] {
        FpaCalibrationInputs in;
        DriftingCamera cam;
        cam.width = kW;
        cam.height = kH;
        const DriftingCameraTruth truth(cam);
        const Band band(8.0, 14.0);
        unsigned seed = 1;
        for (double fpa : {295.65, 303.15, 310.65})
            for (int j = 0; j < 8; ++j)
                in.frames.push_back(truth.frame(band, 278.15 + 8.0 * j, fpa, ++seed));
        RadiometricOptions options;
        options.fpa_degree = 1;
        in.fitted = fit_radiometric(in.frames, kW, kH, band, options);
        in.scene = truth.frame(band, 300.0, 306.0, ++seed);
        return in;
    }();
    return instance;
}

// The fit: design and its pseudo-inverse once, then a 4×24 product per pixel, residuals, bad
// pixels.
void BM_FitFpaCalibration_8SetPoints_3CameraTemperatures(benchmark::State& state) {
    const auto& in = fpa_inputs();
    RadiometricOptions options;
    options.fpa_degree = 1;
    for (auto _ : state) {
        auto cal = fit_radiometric(in.frames, kW, kH, Band(8.0, 14.0), options);
        benchmark::DoNotOptimize(cal.gain.data());
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                            static_cast<std::int64_t>(kN));
}

// Applying it to one frame at its own FPA temperature; items/s ÷ kN = frames per second, to set
// against the camera's frame rate (30–60 Hz for a 640×512 uncooled core).
void BM_ApplyFpaCalibrationPerFrame(benchmark::State& state) {
    const auto& in = fpa_inputs();
    for (auto _ : state) {
        auto radiance = counts_to_radiance(in.fitted, in.scene.counts, in.scene.fpa_temperature_k);
        benchmark::DoNotOptimize(radiance.data());
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                            static_cast<std::int64_t>(kN));
    state.counters["frames_per_s"] =
        benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// Reference in the same run: the single-state inverse of the same frame.
void BM_ApplySingleStateCalibrationPerFrame(benchmark::State& state) {
    const auto& in = fpa_inputs();
    const RadiometricCalibration single =
        at_fpa_temperature(in.fitted, in.scene.fpa_temperature_k, "bench");
    for (auto _ : state) {
        auto radiance = counts_to_radiance(single, in.scene.counts);
        benchmark::DoNotOptimize(radiance.data());
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                            static_cast<std::int64_t>(kN));
    state.counters["frames_per_s"] =
        benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

BENCHMARK(BM_MemoryCopyOfInputs)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FitFpaCalibration_8SetPoints_3CameraTemperatures)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ApplyFpaCalibrationPerFrame)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ApplySingleStateCalibrationPerFrame)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReduceStokesWithUncertainties)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CountsToRadiance)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CountsToStokes)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
