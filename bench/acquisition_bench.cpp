// Requires TIRPOL_WITH_ARAVIS (built only with that back end: cmake/TirpolBackends.cmake).
// Acquisition throughput at 640×512 Mono16 from Aravis's fake GigE Vision camera
// (arv-fake-gv-camera-0.8 on 127.0.0.1, started here):
//   Grab/<fps>                 reference: frames delivered by the camera, nothing else done
//   GrabAverageWriteExr/<fps>  grab → running mean/std (FrameAverager) → EXR (counts, counts_std)
//                              written every 16 frames, as a capture session does per angle
//   AverageWriteExrOnly        the same processing on frames already in memory: the pipeline's own
//                              ceiling without camera or network
// camera_fps is the rate the camera produced frames during the same run, from its frame ids and
// device timestamps (the fake paces itself to period boundaries and slows down, without skipping
// ids, when it lacks CPU time: on a loaded 2-core machine it competes with the pipeline). Each
// iteration is one frame; items_per_second is the sustained frame rate. Compare the two at the same
// requested rate: equal rates with dropped = incomplete = 0 mean the pipeline keeps up with the
// camera; the requested rate of 1000 Hz (the fake's maximum, AcquisitionFramePeriod ≥ 1000 µs)
// shows the ceiling of camera + network stack + pipeline on this machine.

#include <benchmark/benchmark.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <thread>

#include "../tests/acquisition/fake_gv_camera_process.h"
#include "tirpol/acquisition/capture.h"
#include "tirpol/acquisition/frame_gate.h"
#include "tirpol/acquisition/internal/aravis_camera.h"
#include "tirpol/acquisition/internal/sim_stage.h"
#include "tirpol/acquisition/sim/fake_gige_server.h"
#include "tirpol/acquisition/sim/simulated_camera.h"
#include "tirpol/acquisition/sim/stage_simulator.h"
#include "tirpol/acquisition/stage.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/session.h"

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
            problem =
                std::string(test::kFakeGvCameraBinary) + " not found (Debian package aravis-tools)";
            return;
        }
        lock = std::make_unique<test::LoopbackGigELock>();
        process = std::make_unique<test::FakeGvCameraProcess>(*binary, std::vector<std::string>{});
        if (!process->ready()) problem = "the fake GigE Vision camera did not start";
    }
};

/// The shared fake camera, started on first use. GatedCapture serves GVCP on the same loopback port
/// from inside this process and takes the same inter-process lock (an flock on a second descriptor,
/// which would wait forever for the one held here): it stops this camera first with
/// release_fake_camera().
std::optional<FakeCamera>& fake_camera_slot() {
    static std::optional<FakeCamera> camera;
    return camera;
}

FakeCamera& fake_camera() {
    auto& slot = fake_camera_slot();
    if (!slot) slot.emplace();
    return *slot;
}

void release_fake_camera() { fake_camera_slot().reset(); }

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
        return last_ns > first_ns ? static_cast<double>(last_id - first_id) * 1e9 /
                                        static_cast<double>(last_ns - first_ns)
                                  : 0.0;
    }
};

/// The next frame, seen by `probe`; nullopt after handing the grab's error to `state`.
std::optional<Frame> next_frame(benchmark::State& state, Camera& camera, RateProbe& probe) {
    auto frame = camera.grab(std::chrono::seconds(2));
    if (!frame.ok()) {
        state.SkipWithError(frame.error().message.c_str());
        return std::nullopt;
    }
    probe.see(frame.value());
    return std::move(frame.value());
}

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
        const auto frame = next_frame(state, *camera, probe);
        if (!frame) break;
        benchmark::DoNotOptimize(frame->counts.data());
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
        const auto frame = next_frame(state, *camera, probe);
        if (!frame) break;
        averager.add(*frame);
        if (averager.count() == kFramesPerExr) {
            write_exr(dir / ("angle_" + std::to_string(written++ % 4) + ".exr"),
                      averager.to_image());
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
    for (std::size_t i = 0; i < frame.counts.size(); ++i)
        frame.counts[i] = static_cast<float>((i * 7919u) % 65536u);
    const auto dir = std::filesystem::temp_directory_path() / "tirpol-acquisition-bench-only";
    std::filesystem::create_directories(dir);
    FrameAverager averager;
    int written = 0;
    for (auto _ : state) {
        averager.add(frame);
        if (averager.count() == kFramesPerExr) {
            write_exr(dir / ("angle_" + std::to_string(written++ % 4) + ".exr"),
                      averager.to_image());
            averager.reset();
        }
    }
    state.SetItemsProcessed(state.iterations());
    std::filesystem::remove_all(dir);
}

/// 30, 60, 120 and 1000 frames per second (the cameras' rates and a free-running simulator).
void at_camera_frame_rates(benchmark::internal::Benchmark* b) {
    b->Arg(30)
        ->Arg(60)
        ->Arg(120)
        ->Arg(1000)
        ->Iterations(kFramesPerRun)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
}

BENCHMARK(AverageWriteExrOnly)
    ->Iterations(kFramesPerRun)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(Grab)->Apply(at_camera_frame_rates);
BENCHMARK(GrabAverageWriteExr)->Apply(at_camera_frame_rates);

// ---- Full 4-angle set: capture loop overhead
// ------------------------------------------------------- FourAngleSet/<deg_per_s>/<fps>: one
// iteration = run_capture of the default 0/45/90/135 plan (16 frames per angle, no settle) into a
// fresh session: APT stage = the tirpol-stage-sim engine on a pseudo-terminal driven through the
// real serial code; camera = a 640×512 simulated camera free-running at <fps>. Reference in the
// same run: the time the devices alone need, Σ|Δθ|/speed + frames/fps. overhead_ratio = measured /
// reference (1.0 = no overhead; the remainder is serial round trips, the frames the gate discards
// after each move (≈ 1.5 periods), averaging and the 4 EXR + manifest writes).

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
        stage->move_absolute(135.0, std::chrono::seconds(10))
            .value_or_throw();  // where each set ends
        SimulatedCameraConfig config;
        config.width = kWidth;
        config.height = kHeight;
        config.noise_std_counts = 20.0;
        config.frame_rate_hz = fps;  // free-running on its own clock
        SimulatedCamera camera(config, [](double a, std::vector<float>& out) {
            std::fill(
                out.begin(), out.end(),
                static_cast<float>(8000.0 + 500.0 * std::cos(2.0 * a * 3.14159265358979 / 180.0)));
        });
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
            auto session =
                SessionWriter::create(root / std::to_string(run++),
                                      new_session_manifest(camera.info(), stage->info(), plan));
            CaptureOptions options;
            options.progress_stream = nullptr;
            run_capture(camera, *stage, plan, session, options);
            measured_s +=
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        }
        std::filesystem::remove_all(root);
        state.counters["reference_s"] = reference_s;
        state.counters["measured_s"] = measured_s / static_cast<double>(state.iterations());
        state.counters["overhead_ratio"] =
            measured_s / static_cast<double>(state.iterations()) / reference_s;
    }
    stop = true;
    server.join();
}
BENCHMARK(FourAngleSet)
    ->Args({360, 60})
    ->Args({90, 60})
    ->Iterations(3)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// ---- Gated capture at the camera's full rate
// -------------------------------------------------------- GatedCapture/<fps>: the in-process fake
// GigE Vision camera (FakeGigECameraServer, 640×512 Mono16, free-running at <fps> requested — 1000
// is its maximum — over real GVSP on loopback) looks through a sim:// stage turning at 360°/s. In
// the same run:
//   1. the camera alone, before and after the capture: 300 frames grabbed and thrown away each
//   time;
//      camera_fps = the mean of the two, in frames per second of reception time (what the camera +
//      network deliver on this machine now; the load of a shared machine drifts);
//   2. run_capture of 0/45/90/135° × 2 repeats × 64 frames, settle 0, EXR + manifest written by the
//      capture loop's writer thread; capture_fps = delivered frames per second of reception time
//      within the steps (CaptureSummary::delivered_frame_rate_hz).
// ratio = capture_fps / camera_fps (the target is ≥ 0.95); dropped = frames the stream lost during
// the capture (EXR writing stalling the grab shows up here). Each frame carries, noise-free in its
// first row, 100 × the stage's physical angle when it was exposed: a record with any frame from
// another angle has counts_std ≠ 0 there or a mean ≠ 100 × its angle. foreign_records counts them
// (0).
void GatedCapture(benchmark::State& state) {
    release_fake_camera();
    test::LoopbackGigELock gige_lock;
    std::unique_ptr<FakeGigECameraServer> server;
    try {
        server = std::make_unique<FakeGigECameraServer>();
    } catch (const std::exception& e) {
        state.SkipWithError(e.what());
        return;
    }
    SimulatedStageOptions stage_options;
    stage_options.deg_per_s = 360.0;
    auto stage = make_simulated_stage("sim://", stage_options);
    auto angle = simulated_stage_angle_source(*stage);
    server->set_fill([&](const FakeGigEFrameRequest& r, std::vector<float>& counts) {
        std::fill(counts.begin(), counts.end(), 8000.0f);
        const float tag = static_cast<float>(std::round(100.0 * angle()));
        std::fill(counts.begin(), counts.begin() + r.width, tag);
    });
    AravisCameraOptions options;
    options.pixel_format = "Mono16";
    options.width = kWidth;
    options.height = kHeight;
    options.frame_rate_hz = static_cast<double>(state.range(0));
    auto opened = open_aravis_camera(server->device_id(), options);
    if (!opened.ok()) {
        state.SkipWithError(opened.error().message.c_str());
        return;
    }
    Camera& camera = *opened.value();
    CapturePlan plan;
    plan.frames_per_angle = 64;
    plan.repeats = 2;
    plan.settle_s = 0.0;
    char dir_template[] = "/tmp/tirpol-bench-gated-XXXXXX";
    const std::filesystem::path root = ::mkdtemp(dir_template);
    double camera_fps = 0.0, capture_fps = 0.0;
    std::uint64_t dropped = 0, stale = 0, frames = 0;
    int foreign = 0, run = 0;
    for (auto _ : state) {
        // 1. The camera alone, before and after the capture: the machine's load drifts, the mean of
        // the two brackets the capture.
        auto camera_alone_fps = [&] {
            if (!camera.start().ok()) return 0.0;
            (void)camera.grab(std::chrono::seconds(2));  // stream start-up
            FrameGate alone(camera.info().frame_rate_hz);
            for (int i = 0; i < 300; ++i) {
                auto f = camera.grab(std::chrono::seconds(2));
                if (!f.ok()) break;
                alone.exposed_after(f.value(), 0);
            }
            (void)camera.stop();
            return alone.delivered_rate_hz().value_or(0.0);
        };
        const double before_fps = camera_alone_fps();
        // 2. The capture.
        const auto dir = root / std::to_string(run++);
        auto session =
            SessionWriter::create(dir, new_session_manifest(camera.info(), stage->info(), plan));
        CaptureOptions capture_options;
        capture_options.progress_stream = nullptr;
        const std::uint64_t dropped_before = camera.statistics().dropped;
        const CaptureSummary summary = run_capture(camera, *stage, plan, session, capture_options);
        dropped += camera.statistics().dropped - dropped_before;
        capture_fps += summary.delivered_frame_rate_hz.value_or(0.0);
        camera_fps += 0.5 * (before_fps + camera_alone_fps());
        stale += summary.stale_discarded;
        frames += summary.frames;
        const SessionManifest m = read_session(dir);
        for (const auto& r : m.records) {
            const Image image = read_session_frame(dir, m, r);
            const float expected = static_cast<float>(std::round(100.0 * r.angle_deg_requested));
            for (int x = 0; x < kWidth; ++x)
                if (image.channel("counts_std")[static_cast<std::size_t>(x)] != 0.0f ||
                    image.channel("counts")[static_cast<std::size_t>(x)] != expected) {
                    ++foreign;
                    break;
                }
        }
    }
    std::filesystem::remove_all(root);
    const double n = static_cast<double>(state.iterations());
    state.counters["camera_fps"] = camera_fps / n;
    state.counters["capture_fps"] = capture_fps / n;
    state.counters["ratio"] = camera_fps > 0.0 ? capture_fps / camera_fps : 0.0;
    state.counters["dropped"] = static_cast<double>(dropped);
    state.counters["stale"] = static_cast<double>(stale);
    state.counters["frames_kept"] = static_cast<double>(frames);
    state.counters["foreign_records"] = foreign;
}
BENCHMARK(GatedCapture)->Arg(1000)->Iterations(2)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
