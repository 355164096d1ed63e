// Sweep benchmarks, through the real `tirpol sweep` command as a user runs it, on a
// 16-point sweep of the night ball-on-snow scene (128×96 px; uneven: half the points at 16 spp,
// half at 48 spp).
//
// RanksVsThreads: the same sweep with 1 rank × 2 threads (the reference) and `mpirun -np 2` × 1
// thread, measured in the same iteration. ratio_wall = wall(2 ranks)/wall(1 rank) of the whole
// command (including mpirun's start-up); ratio_sweep = the same for the sweep itself (manifest
// wall_seconds: points and results). render_share_* = the renderer's share of a point's time (the
// rest is serial: loading, thermal model, writing EXR/PNG with fsync), which threads do not speed
// up and ranks overlap. scheduling_fraction = mean time a rank other than 0 waited for its next
// point / mean point time (the issue asks ≤ 1 %).

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

namespace {

struct Run {
    double wall_s = 0.0;
    nlohmann::json manifest;
};

Run run_sweep_command(const std::string& prefix, const std::filesystem::path& sweep,
                      const std::filesystem::path& out, int threads) {
    std::filesystem::remove_all(out);
    const std::string cmd =
        fmt::format("{} {} sweep {} -o {} --threads {} -q > /dev/null 2>&1", prefix,
                    TIRPOL_CLI_PATH, sweep.string(), out.string(), threads);
    const auto t0 = std::chrono::steady_clock::now();
    const int status = std::system(cmd.c_str());
    Run r{std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), {}};
    if (status != 0) throw std::runtime_error("failed: " + cmd);
    std::ifstream in(out / "manifest.json");
    r.manifest = nlohmann::json::parse(in);
    return r;
}

void RanksVsThreads(benchmark::State& state) {
    const auto dir = std::filesystem::temp_directory_path() / "tirpol-sweep-bench";
    std::filesystem::create_directories(dir);
    const auto sweep = dir / "sweep.yaml";
    std::ofstream(sweep)
        << "scene: " << TIRPOL_SOURCE_DIR << "/config/scenes/ball_on_snow_night.yaml\n"
        << "set:\n  camera.resolution: [128, 96]\n"
        << "axes:\n  sampling.spp: [16, 48]\n  camera.fov_deg: [16, 18, 20, 22, 24, 26, 28, 30]\n";
    const std::string mpirun = fmt::format(
        "OMPI_MCA_btl_vader_single_copy_mechanism=none {} --allow-run-as-root --oversubscribe "
        "--mca btl self,vader "
        "--mca oob_tcp_if_include lo -np 2",
        TIRPOL_MPIEXEC);
    double one_wall = 0, two_wall = 0, one_sweep = 0, two_sweep = 0, wait = 0, point = 0,
           one_point = 0, one_render = 0, two_render = 0;
    for (auto _ : state) {
        const Run one = run_sweep_command("", sweep, dir / "one", 2);
        const Run two = run_sweep_command(mpirun, sweep, dir / "two", 1);
        one_wall += one.wall_s;
        two_wall += two.wall_s;
        one_sweep += one.manifest["summary"]["wall_seconds"].get<double>();
        two_sweep += two.manifest["summary"]["wall_seconds"].get<double>();
        wait += two.manifest["summary"]["mean_wait_seconds"].get<double>();
        point += two.manifest["summary"]["mean_point_seconds"].get<double>();
        two_render += two.manifest["summary"]["mean_render_seconds"].get<double>();
        one_point += one.manifest["summary"]["mean_point_seconds"].get<double>();
        one_render += one.manifest["summary"]["mean_render_seconds"].get<double>();
        state.SetIterationTime(one.wall_s + two.wall_s);
    }
    const double n = static_cast<double>(state.iterations());
    state.counters["one_rank_2threads_s"] = one_wall / n;
    state.counters["two_ranks_1thread_s"] = two_wall / n;
    state.counters["ratio_wall"] = two_wall / one_wall;
    state.counters["ratio_sweep"] = two_sweep / one_sweep;
    state.counters["wait_per_point_ms"] = 1e3 * wait / n;
    state.counters["point_s"] = point / n;
    // Where a point's time goes: the renderer (threaded) and the rest (scene and thermal set-up,
    // writing).
    state.counters["render_share_1x2"] = one_render / one_point;
    state.counters["render_share_2x1"] = two_render / point;
    state.counters["scheduling_fraction"] = wait / point;
    std::filesystem::remove_all(dir);
}
BENCHMARK(RanksVsThreads)->Iterations(2)->UseManualTime()->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
