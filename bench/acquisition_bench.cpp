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
#include "tirpol/acquisition/capture.h"
#include "tirpol/acquisition/simulated_camera.h"
#include "tirpol/acquisition/stage_registry.h"
#include "tirpol/acquisition/stage_simulator.h"
#include "tirpol/core/session.h"

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <thread>

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


// ---- Full 4-angle set: capture loop overhead -------------------------------------------------------
// FourAngleSet/<deg_per_s>/<fps>: one iteration = run_capture of the default 0/45/90/135 plan
// (16 frames per angle, no settle) into a fresh session: APT stage = the tirpol-stage-sim engine on a
// pseudo-terminal driven through the real serial code; camera = a 640×512 simulated camera paced to
// <fps> like a real one. Reference in the same run: the time the devices alone need, Σ|Δθ|/speed +
// frames/fps. overhead_ratio = measured / reference (1.0 = no overhead; the remainder is serial
// round trips, averaging and the 4 EXR + manifest writes).

/// Benchmark double: delivers the wrapped camera's frames no faster than `fps`, as a real camera does.
class PacedCamera final : public Camera {
public:
    PacedCamera(std::unique_ptr<Camera> inner, double fps) : m_inner(std::move(inner)), m_period(1.0 / fps) {}
    CameraInfo info() const override { return m_inner->info(); }
    Status set_pixel_format(const std::string& f) override { return m_inner->set_pixel_format(f); }
    Status set_frame_rate(double hz) override { return m_inner->set_frame_rate(hz); }
    Status start() override {
        m_next = std::chrono::steady_clock::now();
        return m_inner->start();
    }
    Status stop() override { return m_inner->stop(); }
    Result<Frame> grab(std::chrono::milliseconds timeout) override {
        m_next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(m_period);
        std::this_thread::sleep_until(m_next);
        return m_inner->grab(timeout);
    }
    StreamStatistics statistics() const override { return m_inner->statistics(); }

private:
    std::unique_ptr<Camera> m_inner;
    std::chrono::duration<double> m_period;
    std::chrono::steady_clock::time_point m_next;
};

void FourAngleSet(benchmark::State& state) {
    const double deg_per_s = static_cast<double>(state.range(0));
    const double fps = static_cast<double>(state.range(1));
    StageSimulatorOptions sim_options;
    sim_options.protocol = SimProtocol::Apt;
    sim_options.deg_per_s = deg_per_s;
    sim_options.start_deg = 0.0;
    StageSimulator simulator(sim_options);
    auto pty = PseudoTerminal::open().value_or_throw();
    std::atomic<bool> stop{false};
    std::thread server([&] { serve_stage_simulator(simulator, pty, stop); });
    {
        auto stage = open_stage("thorlabs-apt://" + pty.slave_path()).value_or_throw();
        stage->home(std::chrono::seconds(10)).value_or_throw();
        stage->move_absolute(135.0, std::chrono::seconds(10)).value_or_throw();  // where each set ends
        SimulatedCameraConfig config;
        config.width = kWidth;
        config.height = kHeight;
        config.noise_std_counts = 20.0;
        PacedCamera camera(std::make_unique<SimulatedCamera>(config, [](double a, std::vector<float>& out) {
                               std::fill(out.begin(), out.end(), static_cast<float>(8000.0 + 500.0 * std::cos(2.0 * a * 3.14159265358979 / 180.0)));
                           }),
                           fps);
        CapturePlan plan;
        plan.settle_s = 0.0;
        const double moves_deg = 135.0 + 45.0 * 3.0;  // 135 → 0 → 45 → 90 → 135
        const double reference_s = moves_deg / deg_per_s + 4.0 * plan.frames_per_angle / fps;
        char dir_template[] = "/tmp/tirpol-bench-XXXXXX";
        const std::filesystem::path root = ::mkdtemp(dir_template);
        int run = 0;
        double measured_s = 0.0;
        for (auto _ : state) {
            const auto t0 = std::chrono::steady_clock::now();
            auto session = SessionWriter::create(root / std::to_string(run++), new_session_manifest(camera.info(), stage->info(), plan));
            CaptureOptions options;
            options.progress_stream = nullptr;
            run_capture(camera, *stage, plan, session, options);
            measured_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        }
        std::filesystem::remove_all(root);
        state.counters["reference_s"] = reference_s;
        state.counters["measured_s"] = measured_s / static_cast<double>(state.iterations());
        state.counters["overhead_ratio"] = measured_s / static_cast<double>(state.iterations()) / reference_s;
    }
    stop = true;
    server.join();
}
BENCHMARK(FourAngleSet)->Args({360, 60})->Args({90, 60})->Iterations(3)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
