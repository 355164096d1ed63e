// Overhead of the Python binding of Stokes reduction: tirpol.calibration.reduce called from an
// embedded interpreter on numpy arrays vs the C++ reduce_stokes on the same data, 640×512, 4 angles
// with σ images. Each iteration runs one C++ call and one Python call back to back and times each
// by the CPU time of this process (user + system, page faults included): the Python call reduces on
// a worker thread while the calling thread waits for Ctrl-C (interruptible.h), so the CPU time of
// all threads is what both paths cost; on a shared machine wall time mostly measures the other
// users. The counter `python_over_cpp` is the ratio of the summed times (target ≤ 1.05);
// `*_wall_ms` are reported for reference. What the Python path adds: viewing the float32 numpy
// inputs (no copy), starting the worker thread and wrapping the outputs (moved, not copied) as
// arrays.

#include <benchmark/benchmark.h>
#include <pybind11/embed.h>
#include <pybind11/numpy.h>

#include <chrono>
#include <ctime>
#include <future>
#include <random>

#include "tirpol/calibration/stokes_reduction.h"

namespace py = pybind11;

namespace {

using namespace tirpol::calibration;

constexpr int kW = 640, kH = 512;
const std::vector<double> kAngles{0.0, 45.0, 90.0, 135.0};

std::vector<AnalyzerImage> analyzer_images() {
    std::mt19937 rng(1);
    std::normal_distribution<float> noise(0.0f, 0.05f);
    std::vector<AnalyzerImage> images;
    for (double angle : kAngles) {
        AnalyzerImage a;
        a.angle_deg = angle;
        for (int i = 0; i < kW * kH; ++i) {
            a.signal.push_back(
                10.0f + 0.5f * static_cast<float>(std::cos(2.0 * angle * 3.14159265 / 180.0)) +
                noise(rng));
            a.signal_std.push_back(0.05f);
        }
        images.push_back(std::move(a));
    }
    return images;
}

py::array_t<float> as_array(const std::vector<float>& plane) {
    py::array_t<float> a({kH, kW});
    std::copy(plane.begin(), plane.end(), a.mutable_data());
    return a;
}

double process_cpu_seconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double wall_seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

void BM_ReducePythonVsCpp(benchmark::State& state) {
    const py::object reduce = py::module_::import("tirpol.calibration").attr("reduce");
    const auto images = analyzer_images();
    const auto model = AnalyzerModel::ideal(kAngles);
    py::dict signals, stds;
    for (const auto& a : images) {
        signals[py::float_(a.angle_deg)] = as_array(a.signal);
        stds[py::float_(a.angle_deg)] = as_array(a.signal_std);
    }
    double cpp_s = 0.0, python_s = 0.0, cpp_wall_s = 0.0, python_wall_s = 0.0;
    for (auto _ : state) {
        double cpu = process_cpu_seconds(), wall = wall_seconds();
        // On a worker thread as the binding runs it (interruptible.h): both then allocate their
        // outputs from a thread's malloc arena, whose page reuse differs from the main thread's.
        benchmark::DoNotOptimize(std::async(std::launch::async, [&] {
                                     return reduce_stokes(images, kW, kH, model);
                                 }).get());
        cpp_s += process_cpu_seconds() - cpu;
        cpp_wall_s += wall_seconds() - wall;
        cpu = process_cpu_seconds();
        wall = wall_seconds();
        benchmark::DoNotOptimize(reduce(signals, stds));
        python_s += process_cpu_seconds() - cpu;
        python_wall_s += wall_seconds() - wall;
    }
    const auto n = static_cast<double>(state.iterations());
    state.counters["cpp_ms"] = 1e3 * cpp_s / n;
    state.counters["python_ms"] = 1e3 * python_s / n;
    state.counters["python_over_cpp"] = python_s / cpp_s;
    state.counters["cpp_wall_ms"] = 1e3 * cpp_wall_s / n;
    state.counters["python_wall_ms"] = 1e3 * python_wall_s / n;
}
BENCHMARK(BM_ReducePythonVsCpp)->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace

// One interpreter for the whole program: Google Benchmark calls a benchmark function several times,
// and numpy cannot be imported again into a re-initialised interpreter.
int main(int argc, char** argv) {
    py::scoped_interpreter interpreter;
    py::module_::import("sys").attr("path").attr("insert")(0, TIRPOL_PYTHON_DIR);
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
