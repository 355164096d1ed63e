// Requires TIRPOL_WITH_ARAVIS (built only with that back end: cmake/TirpolBackends.cmake).
// Does an open live-view page slow the camera? Aravis's fake GigE Vision camera
// (arv-fake-gv-camera-0.8 on 127.0.0.1, started here) streams 640×512 Mono16 at 30 fps into a
// LiveView served on loopback. One run measures, in order, three windows of kWindow each:
//   reference  no page open            frames the grab thread received per second
//   page       headless Chromium(s) showing the page (S0 drawn at the browser's pace)
//   reference  no page again           (the two references are averaged: drift cancels)
// Counters: ref_fps, page_fps, ratio = page_fps / ref_fps (the target is ≥ 0.98), dropped (frames
// the stream lost in the page window), cam_ref_fps / cam_page_fps (the rate the fake camera itself
// produced, from frame ids over device time: the fake is a process on the same 2 cores and slows
// down, without skipping ids, when Chromium takes its CPU — a real camera does not), shown_fps
// (frames the page drew per second), and the server process's CPU use (user + system time of every
// thread of this process — Aravis's stream thread, the grab thread, the HTTP threads — over wall
// time, in % of one core) with and without the page. Chromium's own CPU is not counted: it is the
// browser's, as on the operator's laptop. LiveViewDofpFramePath (below) measures a microgrid
// camera's per-frame Stokes path instead.

#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <unistd.h>

#include <sstream>
#include <thread>

#include "../tests/acquisition/child_process.h"
#include "../tests/acquisition/fake_gv_camera_process.h"
#include "httplib_after_eigen.h"
#include "live_view.h"
#include "tirpol/live/live_server.h"

namespace {

using namespace tirpol;
using namespace std::chrono_literals;

constexpr auto kWindow = 8s;
constexpr const char* kCameraUri =
    "aravis://Aravis-Fake-GV01?pixel_format=Mono16&width=640&height=512&fps=30";

double cpu_seconds() {
    rusage u{};
    ::getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
           1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

std::string find_chromium() {
    std::stringstream dirs(std::getenv("PATH") ? std::getenv("PATH") : "/usr/bin");
    for (std::string dir; std::getline(dirs, dir, ':');)
        if (::access((dir + "/chromium").c_str(), X_OK) == 0) return dir + "/chromium";
    return {};
}

struct Window {
    double fps = 0.0, cpu_percent = 0.0;
    double camera_fps = 0.0;  ///< frames the camera produced per second of its own clock (frame
                              ///< ids, device timestamps)
    std::uint64_t dropped = 0;
};

/// Frames the grab thread received per second, and this process's CPU, over one window.
Window measure(const live::LiveView& view) {
    const auto s0 = view.status()["camera"];
    const double cpu0 = cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    std::this_thread::sleep_for(kWindow);
    const auto s1 = view.status()["camera"];
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    Window w;
    w.fps = static_cast<double>(s1["grabbed"].get<std::uint64_t>() -
                                s0["grabbed"].get<std::uint64_t>()) /
            wall;
    w.cpu_percent = 100.0 * (cpu_seconds() - cpu0) / wall;
    w.dropped = s1["dropped"].get<std::uint64_t>() - s0["dropped"].get<std::uint64_t>();
    const auto device_ns = s1["device_timestamp_ns"].get<std::int64_t>() -
                           s0["device_timestamp_ns"].get<std::int64_t>();
    if (device_ns > 0)
        w.camera_fps = 1e9 *
                       static_cast<double>(s1["frame_id"].get<std::uint64_t>() -
                                           s0["frame_id"].get<std::uint64_t>()) /
                       static_cast<double>(device_ns);
    return w;
}

int frames_shown(int port, const std::string& client) {
    httplib::Client http("127.0.0.1", port);
    const auto r = http.Get("/api/observations");
    if (!r || r->status != 200) return 0;
    const auto j = nlohmann::json::parse(r->body);
    return j.contains(client) ? j[client]["frames_shown"].get<int>() : 0;
}

void LiveViewPageOpen(benchmark::State& state) {
    const int pages = static_cast<int>(state.range(0));
    const auto fake = test::find_fake_gv_camera_binary();
    const std::string chromium = find_chromium();
    if (!fake || chromium.empty()) {
        state.SkipWithError("needs arv-fake-gv-camera-0.8 (aravis-tools) and chromium");
        return;
    }
    test::LoopbackGigELock lock;
    test::FakeGvCameraProcess camera(*fake, {});
    if (!camera.ready()) {
        state.SkipWithError("the fake GigE Vision camera did not start");
        return;
    }
    live::LiveViewOptions options;
    options.camera_uri = kCameraUri;
    live::LiveView view(options);
    live::LiveServer server(view, {});
    std::thread serving([&] { server.run(); });
    const auto profile_root = std::filesystem::temp_directory_path() /
                              ("tirpol-live-bench-" + std::to_string(::getpid()));

    for (auto _ : state) {
        std::this_thread::sleep_for(2s);  // stream start-up
        const Window before = measure(view);
        std::vector<std::unique_ptr<test::ChildProcess>> browsers;
        for (int p = 0; p < pages; ++p) {
            const std::string id = "bench" + std::to_string(p);
            browsers.push_back(std::make_unique<test::ChildProcess>(
                std::vector<std::string>{
                    chromium, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
                    "--user-data-dir=" + (profile_root / id).string(), "--window-size=1400,1300",
                    "http://127.0.0.1:" + std::to_string(server.port()) + "/?observe=" + id},
                "/dev/null"));
        }
        for (int i = 0; i < 300 && frames_shown(server.port(), "bench0") < 5; ++i)
            std::this_thread::sleep_for(100ms);
        const int shown0 = frames_shown(server.port(), "bench0");
        const Window page = measure(view);
        const int shown1 = frames_shown(server.port(), "bench0");
        browsers.clear();  // SIGKILL: the pages close
        std::this_thread::sleep_for(1s);
        const Window after = measure(view);
        const double ref = 0.5 * (before.fps + after.fps);
        state.counters["ref_fps"] = ref;
        state.counters["page_fps"] = page.fps;
        state.counters["ratio"] = ref > 0.0 ? page.fps / ref : 0.0;
        state.counters["dropped"] = static_cast<double>(page.dropped);
        state.counters["cam_ref_fps"] = 0.5 * (before.camera_fps + after.camera_fps);
        state.counters["cam_page_fps"] = page.camera_fps;
        // Of the frames the camera produced while the page was open, the share the live view
        // received.
        state.counters["kept"] = page.camera_fps > 0.0 ? page.fps / page.camera_fps : 0.0;
        state.counters["shown_fps"] =
            static_cast<double>(shown1 - shown0) / std::chrono::duration<double>(kWindow).count();
        state.counters["cpu_ref_pct"] = 0.5 * (before.cpu_percent + after.cpu_percent);
        state.counters["cpu_page_pct"] = page.cpu_percent;
    }
    server.stop();
    serving.join();
    std::filesystem::remove_all(profile_root);
}
BENCHMARK(LiveViewPageOpen)->Arg(1)->Arg(2)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

/// The DoFP frame path of the live view: a microgrid camera (the in-process simulated one, 640×512
/// 16-bit Sony-layout mosaics at 60 frames/s, so neither Aravis nor a browser takes the CPU) and
/// one client asking for every new Stokes image (LiveView::stokes_after: demosaic + reduce +
/// S0/DoLP/AoP encoded for the page, once per frame) for kWindow. Counters: cam_fps (frames the
/// grab thread received per second), stokes_fps (Stokes images delivered per second), ratio =
/// stokes_fps / cam_fps (1: every frame shown), cpu_ms_per_image (this process's CPU time, all
/// threads, per Stokes image: the camera's simulation included). Arg: 0 super-pixel, 1 bilinear,
/// 2 newton.
void LiveViewDofpFramePath(benchmark::State& state) {
    const char* methods[] = {"super-pixel", "bilinear", "newton"};
    const char* method = methods[state.range(0)];
    live::LiveViewOptions options;
    options.camera_uri =
        "sim://uniform?width=640&height=512&counts=20000&noise=30&fps=60&bits=16&microgrid=sony";
    options.demosaic = method;
    live::LiveView view(options);
    std::uint64_t sequence = view.stokes_after(0, 5s).sequence;  // the first frame is there
    for (auto _ : state) {
        const auto grabbed0 = view.status()["camera"]["grabbed"].get<std::uint64_t>();
        const double cpu0 = cpu_seconds();
        const auto t0 = std::chrono::steady_clock::now();
        std::uint64_t images = 0;
        while (std::chrono::steady_clock::now() - t0 < kWindow) {
            const live::EncodedImage image = view.stokes_after(sequence, 1s);
            if (!image.bytes) continue;
            sequence = image.sequence;
            ++images;
        }
        const double wall =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const double cpu = cpu_seconds() - cpu0;
        const auto grabbed = view.status()["camera"]["grabbed"].get<std::uint64_t>() - grabbed0;
        state.counters["cam_fps"] = static_cast<double>(grabbed) / wall;
        state.counters["stokes_fps"] = static_cast<double>(images) / wall;
        state.counters["ratio"] =
            grabbed ? static_cast<double>(images) / static_cast<double>(grabbed) : 0.0;
        state.counters["cpu_ms_per_image"] = images ? 1e3 * cpu / static_cast<double>(images) : 0.0;
    }
    state.SetLabel(method);
}
BENCHMARK(LiveViewDofpFramePath)
    ->Arg(0)
    ->Arg(1)
    ->Arg(2)
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
