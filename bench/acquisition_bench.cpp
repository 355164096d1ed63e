// Acquisition throughput at 640×512 Mono16 from Aravis's fake GigE Vision camera
// (arv-fake-gv-camera-0.8 on 127.0.0.1, started here):
//   Grab/<fps>                 reference: frames delivered by the camera, nothing else done
//   GrabAverageWriteExr/<fps>  grab → running mean/std (FrameAverager) → EXR (counts, counts_std)
//                              written every 16 frames, as a capture session does per angle
//   AverageWriteExrOnly        the same processing on frames already in memory: the pipeline's own
//                              ceiling without camera or network
// camera_fps is the rate the camera produced frames during the same run, from its frame ids and device
// timestamps (the fake paces itself to period boundaries and slows down, without skipping ids, when it
// lacks CPU time: on a loaded 2-core machine it competes with the pipeline).
// Each iteration is one frame; items_per_second is the sustained frame rate. Compare the two at the
// same requested rate: equal rates with dropped = incomplete = 0 mean the pipeline keeps up with the
// camera; the requested rate of 1000 Hz (the fake's maximum, AcquisitionFramePeriod ≥ 1000 µs) shows
// the ceiling of camera + network stack + pipeline on this machine.

#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>

#include "../tests/acquisition/fake_gv_camera_process.h"
#include "tirpol/acquisition/aravis_camera.h"
#include "tirpol/acquisition/frame_averager.h"
#include "tirpol/core/exr_io.h"

namespace {

using namespace tirpol;
using namespace tirpol::acquisition;

constexpr int kWidth = 640, kHeight = 512;
constexpr int kFramesPerExr = 16;
constexpr int kFramesPerRun = 320;

/// The fake camera process, shared by every benchmark of this run.
struct FakeCamera {
    std::unique_ptr<test::LoopbackGigELock> lock;
    std::unique_ptr<test::FakeGvCameraProcess> process;
    std::string problem;

    FakeCamera() {
        const auto binary = test::find_fake_gv_camera_binary();
        if (!binary) {
            problem = std::string(test::kFakeGvCameraBinary) + " not found (Debian package aravis-tools)";
            return;
        }
        lock = std::make_unique<test::LoopbackGigELock>();
        process = std::make_unique<test::FakeGvCameraProcess>(*binary, std::vector<std::string>{});
        if (!process->ready()) problem = "the fake GigE Vision camera did not start";
    }
};

FakeCamera& fake_camera() {
    static FakeCamera camera;
    return camera;
}

std::unique_ptr<Camera> open_streaming_camera(benchmark::State& state, double fps) {
    if (!fake_camera().problem.empty()) {
        state.SkipWithError(fake_camera().problem.c_str());
        return nullptr;
    }
    AravisCameraOptions options;
    options.pixel_format = "Mono16";
    options.width = kWidth;
    options.height = kHeight;
    options.frame_rate_hz = fps;
    options.stream_buffers = 64;
    auto camera = open_aravis_camera(test::kFakeGvCameraId, options);
    if (!camera.ok()) {
        state.SkipWithError(camera.error().message.c_str());
        return nullptr;
    }
    if (Status s = camera.value()->start(); !s.ok()) {
        state.SkipWithError(s.error().message.c_str());
        return nullptr;
    }
    return std::move(camera.value());
}

/// First and last frame seen, for the camera's own rate over the run.
struct RateProbe {
    std::uint64_t first_id = 0, last_id = 0;
    std::int64_t first_ns = 0, last_ns = 0;
    void see(const Frame& f) {
        if (first_id == 0) {
            first_id = f.frame_id;
            first_ns = f.device_timestamp_ns;
        }
        last_id = f.frame_id;
        last_ns = f.device_timestamp_ns;
    }
    double fps() const {
        return last_ns > first_ns ? static_cast<double>(last_id - first_id) * 1e9 / static_cast<double>(last_ns - first_ns) : 0.0;
    }
};

void report(benchmark::State& state, Camera& camera, const RateProbe& probe) {
    state.counters["camera_fps"] = probe.fps();
    const StreamStatistics stats = camera.statistics();
    state.SetItemsProcessed(static_cast<std::int64_t>(stats.delivered));
    state.counters["dropped"] = static_cast<double>(stats.dropped);
    state.counters["incomplete"] = static_cast<double>(stats.incomplete);
    state.counters["requested_fps"] = static_cast<double>(state.range(0));
}

void Grab(benchmark::State& state) {
    auto camera = open_streaming_camera(state, static_cast<double>(state.range(0)));
    if (!camera) return;
    (void)camera->grab(std::chrono::seconds(2));  // the first frame includes stream start-up
    RateProbe probe;
    for (auto _ : state) {
        auto frame = camera->grab(std::chrono::seconds(2));
        if (!frame.ok()) {
            state.SkipWithError(frame.error().message.c_str());
            break;
        }
        benchmark::DoNotOptimize(frame.value().counts.data());
        probe.see(frame.value());
    }
    report(state, *camera, probe);
}

void GrabAverageWriteExr(benchmark::State& state) {
    auto camera = open_streaming_camera(state, static_cast<double>(state.range(0)));
    if (!camera) return;
    const auto dir = std::filesystem::temp_directory_path() / "tirpol-acquisition-bench";
    std::filesystem::create_directories(dir);
    FrameAverager averager;
    int written = 0;
    (void)camera->grab(std::chrono::seconds(2));
    RateProbe probe;
    for (auto _ : state) {
        auto frame = camera->grab(std::chrono::seconds(2));
        if (!frame.ok()) {
            state.SkipWithError(frame.error().message.c_str());
            break;
        }
        probe.see(frame.value());
        averager.add(frame.value());
        if (averager.count() == kFramesPerExr) {
            write_exr(dir / ("angle_" + std::to_string(written++ % 4) + ".exr"), averager.to_image());
            averager.reset();
        }
    }
    report(state, *camera, probe);
    state.counters["exr_files"] = written;
    std::filesystem::remove_all(dir);
}

void AverageWriteExrOnly(benchmark::State& state) {
    Frame frame;
    frame.width = kWidth;
    frame.height = kHeight;
    frame.counts.resize(static_cast<std::size_t>(kWidth) * kHeight);
    for (std::size_t i = 0; i < frame.counts.size(); ++i) frame.counts[i] = static_cast<float>((i * 7919u) % 65536u);
    const auto dir = std::filesystem::temp_directory_path() / "tirpol-acquisition-bench-only";
    std::filesystem::create_directories(dir);
    FrameAverager averager;
    int written = 0;
    for (auto _ : state) {
        averager.add(frame);
        if (averager.count() == kFramesPerExr) {
            write_exr(dir / ("angle_" + std::to_string(written++ % 4) + ".exr"), averager.to_image());
            averager.reset();
        }
    }
    state.SetItemsProcessed(state.iterations());
    std::filesystem::remove_all(dir);
}

BENCHMARK(AverageWriteExrOnly)->Iterations(kFramesPerRun)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(Grab)->Arg(30)->Arg(60)->Arg(120)->Arg(1000)->Iterations(kFramesPerRun)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(GrabAverageWriteExr)
    ->Arg(30)->Arg(60)->Arg(120)->Arg(1000)
    ->Iterations(kFramesPerRun)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
