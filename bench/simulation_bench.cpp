// Renderer throughput on a paper scene (nine panels under a clear night sky) at 640×512, against the
// raw Embree ray-cast throughput of the same scene and camera rays measured in the same run, so the
// cost of polarized shading is a ratio. Also: S1 noise on a flat panel (spatial std over its pixels,
// which are uniform in expectation) versus time for a few samples-per-pixel and bounce settings, and
// memory. Run: build/bench/tirpol_simulation_bench (from inside the source tree).

#include <benchmark/benchmark.h>

#include <chrono>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "tirpol/core/source_tree.h"
#include "tirpol/core/error.h"
#include "tirpol/simulation/renderer.h"
#include "tirpol/simulation/scene.h"

namespace {

using namespace tirpol;
using namespace tirpol::simulation;

std::filesystem::path find_scene(const std::string& name) { return find_config("scenes/" + name); }

double peak_rss_mb() {
    std::ifstream status("/proc/self/status");
    std::string key;
    while (status >> key) {
        if (key == "VmHWM:") {
            double kb = 0.0;
            status >> kb;
            return kb / 1024.0;
        }
        status.ignore(1 << 20, '\n');
    }
    return 0.0;
}

/// Spatial std of S1 over the pixels of object `name` away from its edges (a flat, uniform panel),
/// and (in `reported_sigma`) the median of the renderer's own per-pixel error √S1_var there.
double s1_noise_on(const Scene& scene, const Image& img, const std::string& name, double& reported_sigma) {
    std::uint32_t id = 0;
    while (id < scene.objects.size() && scene.objects[id].name != name) ++id;
    std::vector<double> values, sigmas;
    for (int y = 2; y < img.height() - 2; ++y)
        for (int x = 2; x < img.width() - 2; ++x) {
            bool inside = true;
            for (int d = -2; d <= 2 && inside; ++d)
                inside = img.at("object_id", x + d, y) == static_cast<float>(id) && img.at("object_id", x, y + d) == static_cast<float>(id);
            if (inside) {
                values.push_back(img.at("S1", x, y));
                sigmas.push_back(std::sqrt(img.at("S1_var", x, y)));
            }
        }
    std::nth_element(sigmas.begin(), sigmas.begin() + static_cast<std::ptrdiff_t>(sigmas.size() / 2), sigmas.end());
    reported_sigma = sigmas[sigmas.size() / 2];
    double mean = 0.0, var = 0.0;
    for (double v : values) mean += v;
    mean /= static_cast<double>(values.size());
    for (double v : values) var += (v - mean) * (v - mean);
    return std::sqrt(var / static_cast<double>(values.size() - 1));
}

/// Casts the camera rays of every pixel and sample (no shading) through the same BVH.
double embree_rays_per_second(const Scene& scene, int spp) {
    const auto start = std::chrono::steady_clock::now();
    int hits = 0;
    std::size_t rays = 0;
    for (int y = 0; y < scene.camera.height(); ++y)
        for (int x = 0; x < scene.camera.width(); ++x)
            for (int s = 0; s < spp; ++s) {
                const Vec3 d = scene.camera.ray_direction(x + (s + 0.5) / spp, y + 0.5);
                hits += scene.tracer->intersect(scene.camera.position(), d).has_value() ? 1 : 0;
                ++rays;
            }
    benchmark::DoNotOptimize(hits);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return static_cast<double>(rays) / seconds;
}

void BM_RenderPanels640x512(benchmark::State& state) {
    const int spp = static_cast<int>(state.range(0));
    const int bounces = static_cast<int>(state.range(1));
    Scene scene = load_scene(find_scene("panels_night.yaml"));
    scene.camera = scene.camera.resized(640, 512);
    scene.sampling.samples_per_pixel = spp;
    scene.sampling.max_bounces = bounces;
    RenderStatistics stats;
    Image img;
    for (auto _ : state) {
        img = render(scene, {}, &stats);
        state.SetIterationTime(stats.seconds);
    }
    // The Embree reference runs on one thread: the shading overhead compares rays per thread-second.
    const double embree_rps = embree_rays_per_second(scene, 1);
    const double trace_seconds = stats.seconds - stats.setup_seconds;
    const double render_rps = static_cast<double>(stats.scene_rays + stats.shadow_rays) / trace_seconds;
    const double threads = std::max(1u, std::thread::hardware_concurrency());
    const double nedt_radiance = 0.08 * scene.band.radiance_dT(280.0);  // the paper's camera NEDT, 80 mK (§3.1)
    state.counters["seconds"] = stats.seconds;
    state.counters["table_seconds"] = stats.setup_seconds;
    state.counters["Mrays_per_s"] = render_rps * 1e-6;
    state.counters["embree_1thread_Mrays_per_s"] = embree_rps * 1e-6;
    state.counters["shading_overhead"] = embree_rps / (render_rps / threads);
    double reported_sigma = 0.0;
    state.counters["s1_noise"] = s1_noise_on(scene, img, "panel_matte_white_paint", reported_sigma);
    state.counters["s1_reported_sigma"] = reported_sigma;
    state.counters["s1_noise_over_nedt"] = state.counters["s1_noise"] / nedt_radiance;
    state.counters["geometry_MB"] = static_cast<double>(scene.tracer->memory_bytes()) / 1048576.0;
    state.counters["peak_rss_MB"] = peak_rss_mb();
    std::printf("render 640x512 spp=%d bounces=%d: %.2f s (%.2f s tables), %.2f Mrays/s (all threads), Embree alone %.2f Mrays/s (1 thread), "
                "overhead ×%.1f per ray, S1 noise %.4g W/(m²·sr) = %.2f × NEDT(80 mK) (median reported σ %.4g)\n",
                spp, bounces, stats.seconds, stats.setup_seconds, render_rps * 1e-6, embree_rps * 1e-6,
                static_cast<double>(state.counters["shading_overhead"]), static_cast<double>(state.counters["s1_noise"]),
                static_cast<double>(state.counters["s1_noise_over_nedt"]), reported_sigma);
}
BENCHMARK(BM_RenderPanels640x512)
    ->Args({4, 4})
    ->Args({16, 4})
    ->Args({16, 1})
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kSecond);

/// Embree alone: the camera rays of the same scene at 640×512, single thread.
void BM_EmbreeCameraRays640x512(benchmark::State& state) {
    Scene scene = load_scene(find_scene("panels_night.yaml"));
    scene.camera = scene.camera.resized(640, 512);
    double rps = 0.0;
    for (auto _ : state) rps = embree_rays_per_second(scene, 1);
    state.counters["Mrays_per_s"] = rps * 1e-6;
}
BENCHMARK(BM_EmbreeCameraRays640x512)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
