// Renderer speed, as ratios measured in one run (docs/simulation.md "Speed"):
//  - ShadingOverhead: CPU time of a render's pixel loop over the CPU time of bare rtcIntersect1 /
//    rtcOccluded1 replaying exactly the rays that render cast (camera, bounce, shadow and auxiliary
//    rays, recorded in order), both on one thread: what the polarized shading costs per ray (median
//    of 5 repetitions, each one render against 8 replays).
//  - PanelsNightEqualNoise: panels_night at 640×512 rendered to a mean per-pixel S1 standard error
//  of
//    0.042 W/(m²·sr) over surfaces (the spp is predicted from a pilot render, σ ∝ 1/√spp).
//  - ReflectionEqualNoise: config/scenes/reflection_compare.yaml, the time to a relative linear-
//    polarization noise of 1 %, measured from two renders with different seeds, each renderer run
//    at doubling spp from 16 until its noise is ≤ 1 % and its time interpolated in log-log between
//    the two runs that bracket 1 % (no 1/√N extrapolation); the same for Mitsuba 3 with each of its
//    samplers (independent, stratified, multijitter, orthogonal, ldsampler; TIRPOL_MITSUBA_SAMPLERS
//    picks some) when TIRPOL_MITSUBA names its `mitsuba` executable (built scalar_mono_polarized),
//    else skipped, after checking per object that both renderers' mean Stokes agree (else no
//    ratio); the ratio against the best sampler is printed.
//  - ShadingProfile: panels_night 80×64, 8 and 64 spp, one thread: the callgrind workload.
//  - ThreadEfficiency: panels_night 320×256, 32 spp, at 1, 2, 4, … threads up to
//    hardware_concurrency: wall time, speedup, efficiency and tracing CPU per million paths.
//  - ErrorBarTails (figures, not speed): per-pixel z tails against spp in an isothermal enclosure
//    (plain estimator) and an open scene against a 4096-spp reference (control variate).
//  - VarianceCalibration (figures): per material region of three night scenes, the two-seed ratio
//    ⟨(a − b)²⟩/⟨var_a + var_b⟩ (1 when the variance channels are unbiased) ± its standard error at
//    8, 32, 128 spp, both estimators.
//  - ReplicateCount (figures): noise at 64 and 256 spp for 1, 4, 8, 16, 32 replicates.
//  - ConvergenceExponent (figures): relative S1/S2 noise at 16, 64, 256 spp on reflection_compare
//    and panels_night (emission-dominated), and the fitted exponent of noise ∝ spp^a.
// Run: build/bench/tirpol_simulation_bench (from inside the source tree).

#include <benchmark/benchmark.h>
#include <fmt/format.h>
#include <sys/resource.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <limits>
#include <mutex>
#include <numeric>
#include <string>
#include <thread>
#include <vector>

#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/source_tree.h"
#include "tirpol/core/stokes_frame.h"
#include "tirpol/simulation/renderer.h"
#include "tirpol/simulation/scene.h"

namespace {

using namespace tirpol;
using namespace tirpol::simulation;

double thread_cpu_seconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// Every ray of a render, in the order it was cast (single-threaded recording).
class RayLog final : public RayRecorder {
public:
    struct Ray {
        float origin[3], direction[3];
        bool occlusion;
    };
    void record(const Vec3& o, const Vec3& d, double /*t_max*/, bool occlusion) override {
        const std::lock_guard lock(m_mutex);
        rays.push_back(
            {{static_cast<float>(o.x()), static_cast<float>(o.y()), static_cast<float>(o.z())},
             {static_cast<float>(d.x()), static_cast<float>(d.y()), static_cast<float>(d.z())},
             occlusion});
    }
    std::vector<Ray> rays;

private:
    std::mutex m_mutex;
};

/// CPU seconds to cast `log`'s rays through the scene's BVH with bare Embree queries, one thread.
double replay_cpu_seconds(const RayTracer& tracer, const RayLog& log) {
    const double start = thread_cpu_seconds();
    double checksum = 0.0;
    for (const auto& r : log.rays) {
        const Vec3 o(r.origin[0], r.origin[1], r.origin[2]),
            d(r.direction[0], r.direction[1], r.direction[2]);
        if (r.occlusion)
            checksum += tracer.occluded(o, d, 0.0, 1e30) ? 1.0 : 0.0;
        else
            checksum += std::min(tracer.nearest_distance(o, d), 1e3);
    }
    benchmark::DoNotOptimize(checksum);
    return thread_cpu_seconds() - start;
}

void BM_ShadingOverhead(benchmark::State& state) {
    // Each repetition times one render and enough replays of its rays to cost about as much CPU (a
    // lone 0.07 s replay is at the mercy of the other jobs' cache traffic); the overhead is the
    // median over the repetitions, and the spread of the repetitions is printed with it.
    constexpr int kRepetitions = 5, kReplaysPerRepetition = 8;
    Scene scene = load_scene(find_config("scenes/panels_night.yaml"));
    scene.camera = scene.camera.resized(320, 256);
    scene.sampling.samples_per_pixel = 8;
    RenderOptions one_thread;
    one_thread.threads = 1;
    RayLog log;
    RenderOptions recording = one_thread;
    recording.ray_recorder = &log;
    RenderStatistics stats;
    render(scene, recording, &stats);
    const auto recorded = static_cast<double>(log.rays.size());
    std::vector<double> render_cpu, replay_cpu, overhead;
    for (auto _ : state) {
        for (int r = 0; r < kRepetitions; ++r) {
            render(scene, one_thread, &stats);
            double replay = 0.0;
            for (int k = 0; k < kReplaysPerRepetition; ++k)
                replay += replay_cpu_seconds(*scene.tracer, log);
            render_cpu.push_back(stats.trace_cpu_seconds);
            replay_cpu.push_back(replay / kReplaysPerRepetition);
            overhead.push_back(render_cpu.back() / replay_cpu.back());
        }
        state.SetIterationTime(std::accumulate(render_cpu.begin(), render_cpu.end(), 0.0));
    }
    const auto median = [](std::vector<double> v) {
        std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
        return v[v.size() / 2];
    };
    const auto [lo, hi] = std::minmax_element(overhead.begin(), overhead.end());
    state.counters["rays"] = recorded;
    state.counters["render_cpu_s"] = median(render_cpu);
    state.counters["embree_cpu_s"] = median(replay_cpu);
    state.counters["overhead"] = median(overhead);
    std::printf(
        "shading overhead, panels_night 320x256 spp=8, %.0f rays (%.2f per camera path): render "
        "%.3f CPU s, "
        "bare Embree replay %.4f CPU s (medians of %d), ratio %.2f (repetitions %.2f-%.2f)\n",
        recorded, recorded / (320.0 * 256.0 * 8.0), median(render_cpu), median(replay_cpu),
        kRepetitions, median(overhead), *lo, *hi);
}
BENCHMARK(BM_ShadingOverhead)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);

/// The callgrind workload (docs/simulation.md "Where the time goes"): panels_night at 80×64, 8 spp
/// (1 point in each of 8 replicates, as ShadingOverhead) and 64 spp (4 points in each of 16), one
/// thread, the scene's emissivity tables already cached by a first 1-spp render. Small enough that
/// `valgrind --tool=callgrind` finishes in a minute; its instruction counts do not depend on load.
void BM_ShadingProfile(benchmark::State& state) {
    Scene scene = load_scene(find_config("scenes/panels_night.yaml"));
    scene.camera = scene.camera.resized(80, 64);
    scene.sampling.samples_per_pixel = 1;
    RenderOptions one_thread;
    one_thread.threads = 1;
    RenderStatistics stats;
    render(scene, one_thread, &stats);
    scene.sampling.samples_per_pixel = static_cast<int>(state.range(0));
    std::uint64_t checksum = 0xcbf29ce484222325ULL;  // FNV-1a over the Stokes channels' bits
    for (auto _ : state) {
        const Image image = render(scene, one_thread, &stats);
        for (const char* c : {"S0", "S1", "S2", "S3", "S0_var", "S1_var", "S2_var", "S3_var"})
            for (const float v : image.channel(c)) {
                std::uint32_t bits = 0;
                std::memcpy(&bits, &v, sizeof bits);
                checksum = (checksum ^ bits) * 0x100000001b3ULL;
            }
        state.SetIterationTime(stats.trace_cpu_seconds);
    }
    // Equal checksums of two builds: bitwise-identical images.
    std::printf("shading profile render, %d spp: %llu scene rays, Stokes checksum %016llx\n",
                scene.sampling.samples_per_pixel, static_cast<unsigned long long>(stats.scene_rays),
                static_cast<unsigned long long>(checksum));
    state.counters["scene_rays"] = static_cast<double>(stats.scene_rays);
}
BENCHMARK(BM_ShadingProfile)
    ->Arg(8)
    ->Arg(64)
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kSecond);

/// Thread scaling on PanelsNightEqualNoise-like work (panels_night 320×256 at 32 spp): wall time
/// with 1, 2, 4, … threads up to hardware_concurrency (and it), the speedup over one thread and the
/// efficiency speedup/threads, with the tracing CPU per million paths (a rise with threads is time
/// lost to sharing: cache lines, the allocator, memory bandwidth). Needs otherwise idle cores.
void BM_ThreadEfficiency(benchmark::State& state) {
    Scene scene = load_scene(find_config("scenes/panels_night.yaml"));
    scene.camera = scene.camera.resized(320, 256);
    scene.sampling.samples_per_pixel = 32;
    const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
    std::vector<int> counts;
    for (unsigned t = 1; t < hardware; t *= 2) counts.push_back(static_cast<int>(t));
    counts.push_back(static_cast<int>(hardware));
    render(scene);  // emissivity tables into the cache
    const double paths = 320.0 * 256.0 * 32.0;
    for (auto _ : state) {
        double one_thread_s = 0.0;
        for (const int threads : counts) {
            RenderOptions options;
            options.threads = threads;
            RenderStatistics stats;
            render(scene, options, &stats);
            const double wall_s = stats.seconds - stats.setup_seconds;
            if (threads == 1) one_thread_s = wall_s;
            const double speedup = one_thread_s / wall_s;
            std::printf(
                "threads %2d: %.3f s, speedup %.2f, efficiency %.2f, tracing %.3f CPU s per "
                "million paths\n",
                threads, wall_s, speedup, speedup / threads,
                stats.trace_cpu_seconds / (paths * 1e-6));
            state.counters[fmt::format("efficiency_{}", threads)] = speedup / threads;
        }
        state.SetIterationTime(1.0);
    }
}
BENCHMARK(BM_ThreadEfficiency)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);

/// Mean of √S1_var over the pixels whose centre ray hits a surface.
double mean_s1_standard_error(const Image& img) {
    double sum = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < img.pixel_count(); ++i)
        if (img.channel("object_id")[i] >= 0.0f) {
            sum += std::sqrt(img.channel("S1_var")[i]);
            ++n;
        }
    return sum / static_cast<double>(std::max<std::size_t>(n, 1));
}

void BM_PanelsNightEqualNoise(benchmark::State& state) {
    constexpr double kTargetW = 0.042;  // W/(m²·sr): ≈ 50 mK NEDT in 8–14 µm near 280 K
    // 16, not 8: the mean of √var over pixels is biased low by few-dof variance estimates (c4 ≈
    // 0.94 at 4 dof), so an 8-spp pilot predicted too few samples (63 spp → 0.0455 instead of
    // 0.042).
    constexpr int kPilotSpp = 16;
    Scene scene = load_scene(find_config("scenes/panels_night.yaml"));
    scene.camera = scene.camera.resized(640, 512);
    scene.sampling.samples_per_pixel = kPilotSpp;
    RenderStatistics pilot_stats, stats;
    const Image pilot = render(scene, {}, &pilot_stats);
    const double pilot_error = mean_s1_standard_error(pilot);
    // The error bars are conservative (docs/simulation.md, "What the variance channels mean"): the
    // S1 noise a second seed actually shows, √(mean (a − b)²/2) over surfaces, against the reported
    // one.
    Scene second_seed = scene;
    second_seed.sampling.seed = scene.sampling.seed + 1;
    const Image pilot_b = render(second_seed);
    double reported_var = 0.0, actual_var = 0.0;
    std::size_t surfaces = 0;
    for (std::size_t i = 0; i < pilot.pixel_count(); ++i)
        if (pilot.channel("object_id")[i] >= 0.0f) {
            const double d = pilot.channel("S1")[i] - pilot_b.channel("S1")[i];
            actual_var += 0.5 * d * d;
            reported_var += 0.5 * (pilot.channel("S1_var")[i] + pilot_b.channel("S1_var")[i]);
            ++surfaces;
        }
    std::printf(
        "panels_night 640x512 %d spp: rms S1 standard error reported %.4f, shown by two seeds %.4f "
        "W/(m2 sr)\n",
        kPilotSpp, std::sqrt(reported_var / static_cast<double>(surfaces)),
        std::sqrt(actual_var / static_cast<double>(surfaces)));
    const int spp = static_cast<int>(std::ceil(kPilotSpp * std::pow(pilot_error / kTargetW, 2.0)));
    scene.sampling.samples_per_pixel = spp;
    double error = 0.0;
    for (auto _ : state) {
        error = mean_s1_standard_error(render(scene, {}, &stats));
        state.SetIterationTime(stats.seconds);
    }
    state.counters["spp"] = spp;
    state.counters["seconds"] = stats.seconds;
    state.counters["setup_seconds"] = stats.setup_seconds;
    state.counters["s1_std_error"] = error;
    state.counters["cpu_s_per_Mpath"] = stats.trace_cpu_seconds / (640.0 * 512.0 * spp * 1e-6);
    state.counters["trace_cpu_s"] = stats.trace_cpu_seconds;
    std::printf(
        "panels_night 640x512: pilot %d spp -> mean S1 std error %.4f; %d spp -> %.4f W/(m2 sr) in "
        "%.2f s "
        "(%.2f s emissivity tables, %.1f CPU s tracing, i.e. %.1f s on 2 otherwise idle cores)\n",
        kPilotSpp, pilot_error, spp, error, stats.seconds, stats.setup_seconds,
        stats.trace_cpu_seconds, stats.setup_seconds + 0.5 * stats.trace_cpu_seconds);
}
BENCHMARK(BM_PanelsNightEqualNoise)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);

/// Tails of z = (S − truth)/√(var + var_truth) over the surface pixels' S0, S1, S2: the share of
/// |z| beyond 3 and 5, the largest |z| and the mean z² (a Gaussian: 0.27 %, 5.7e-7, ~4.5 over 10⁴
/// values, 1).
struct ZTails {
    double beyond3 = 0.0, beyond5 = 0.0, max_abs = 0.0, mean_square = 0.0;
};

/// `truth` is either a reference render (its S*_var adds to the variance) or, when null, the
/// isothermal enclosure's exact (L_bb, 0, 0). σ is floored at 1e-6·l_bb for pixels with
/// deterministic paths.
ZTails z_tails(const Image& img, const Image* truth, double l_bb) {
    const std::array<std::string, 3> stokes{"S0", "S1", "S2"};
    std::vector<double> z;
    for (std::size_t i = 0; i < img.pixel_count(); ++i) {
        if (img.channel("object_id")[i] < 0.0f) continue;
        for (std::size_t c = 0; c < stokes.size(); ++c) {
            double expected = c == 0 ? l_bb : 0.0,
                   var = img.channel(stokes[c] + "_var")[i] + 1e-12 * l_bb * l_bb;
            if (truth) {
                expected = truth->channel(stokes[c])[i];
                var += truth->channel(stokes[c] + "_var")[i];
            }
            z.push_back(std::abs(img.channel(stokes[c])[i] - expected) / std::sqrt(var));
        }
    }
    ZTails t;
    for (const double v : z) {
        t.beyond3 += v > 3.0 ? 1.0 : 0.0;
        t.beyond5 += v > 5.0 ? 1.0 : 0.0;
        t.max_abs = std::max(t.max_abs, v);
        t.mean_square += v * v;
    }
    const auto n = static_cast<double>(std::max<std::size_t>(z.size(), 1));
    t.beyond3 /= n;
    t.beyond5 /= n;
    t.mean_square /= n;
    return t;
}

/// A metal mirror (n = 12 + 60i) tilted 95° reflects the camera's horizontal view onto a ground of
/// `material` seen 75–85° off its normal ("mirrors viewing glossy paint"), 48×36 pixels.
Scene mirror_over_ground(const std::filesystem::path& dir, const std::string& material,
                         const std::string& sky, double ground_k, int spp, std::uint64_t seed) {
    const std::string yaml = fmt::format(
        "band: {{lo_um: 8, hi_um: 14}}\nsampling: {{spp: {}, seed: {}}}\nmaterials_dir: {}\n"
        "camera: {{resolution: [48, 36], fov_deg: 30, position: [0, -3, 1.0], look_at: [0, 1, "
        "1.0]}}\nsky: {}\n"
        "objects:\n  - {{name: ground, geometry: {{type: plane, size: [30, 30]}}, material: {}, "
        "temperature: {}}}\n"
        "  - {{name: mirror, geometry: {{type: plane, size: [4, 3]}}, transform: {{translate: [0, "
        "1, 1.0], "
        "rotate_deg: [95, 0, 0]}}, material: {{name: metal_mirror, source: bench, model: "
        "smooth_fresnel, "
        "refractive_index: {{n: 12, k: 60}}}}, temperature: 290}}\n",
        spp, seed, find_config("materials").string(), sky, material, ground_k);
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "mirror.yaml") << yaml;
    return load_scene(dir / "mirror.yaml");
}

/// Issue 13's error-bar goal as figures: for 16, 64 and 256 spp, the z tails (a) of the isothermal
/// enclosure (290 K) with the plain estimator, the library's glossy and rough materials as the
/// ground, and (b) of an open scene (ground at 300 K under a 270 K clear sky, control variate on)
/// against a 4096-spp reference render with another seed. Not a speed benchmark: it prints figures.
void BM_ErrorBarTails(benchmark::State& state) {
    const auto dir = std::filesystem::temp_directory_path() / "tirpol_error_bar_bench";
    const std::string isothermal_sky = "{type: uniform, temperature: 290}";
    const std::string open_sky = "{type: clear_sky, air_temperature: 270, zenith_emissivity: 0.65}";
    RenderOptions plain;
    plain.control_variate = false;
    for (auto _ : state) {
        for (const char* material :
             {"glossy_black_paint", "automotive_clear_coat", "bare_aluminium", "concrete"}) {
            Scene reference = mirror_over_ground(dir, material, open_sky, 300.0, 4096, 99);
            const Image open_reference = render(reference);
            for (const int spp : {16, 64, 256}) {
                const Scene isothermal =
                    mirror_over_ground(dir, material, isothermal_sky, 290.0, spp, 7);
                const ZTails iso =
                    z_tails(render(isothermal, plain), nullptr, isothermal.band.radiance(290.0));
                const Scene open = mirror_over_ground(dir, material, open_sky, 300.0, spp, 7);
                const ZTails cv = z_tails(render(open), &open_reference, open.band.radiance(290.0));
                std::printf(
                    "%-22s %3d spp | isothermal, plain: |z|>3 %.3f %%, |z|>5 %.3f %%, max %.2f, "
                    "mean z2 %.3f | "
                    "open, control variate, vs 4096 spp: |z|>3 %.3f %%, |z|>5 %.3f %%, max %.2f, "
                    "mean z2 %.3f\n",
                    material, spp, 100.0 * iso.beyond3, 100.0 * iso.beyond5, iso.max_abs,
                    iso.mean_square, 100.0 * cv.beyond3, 100.0 * cv.beyond5, cv.max_abs,
                    cv.mean_square);
            }
        }
        state.SetIterationTime(1.0);
    }
    std::filesystem::remove_all(dir);
}
BENCHMARK(BM_ErrorBarTails)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);

// ---- ReflectionEqualNoise: tirpol against Mitsuba 3 on the same scene ----

const std::array<std::string, 4> kStokesChannels = {"S0", "S1", "S2", "S3"};

/// Two renders of one renderer with independent seeds, channels S0..S3 in tirpol's image Stokes
/// frame.
struct RenderPair {
    Image a, b;
    double seconds =
        0.0;  ///< per render: the sample loop's wall time (scene loading, tables excluded)
    double cpu_seconds =
        0.0;  ///< per render, summed over threads (tirpol: pixel loop; Mitsuba: process)
    int samples_per_pixel = 0;  ///< as rendered (Mitsuba's samplers round some counts up)
};

/// Relative linear-polarization noise of one render of `p` over the pixels `mask`:
/// √(mean over pixels of ((a−b)²/2 in S1 and S2)) / mean S0.
double relative_linear_noise(const RenderPair& p, const std::vector<bool>& mask) {
    double var = 0.0, s0 = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < mask.size(); ++i) {
        if (!mask[i]) continue;
        for (const char* c : {"S1", "S2"}) {
            const double d = p.a.channel(c)[i] - p.b.channel(c)[i];
            var += 0.5 * d * d;
        }
        s0 += 0.5 * (p.a.channel("S0")[i] + p.b.channel("S0")[i]);
        ++n;
    }
    return std::sqrt(var / static_cast<double>(n)) / (s0 / static_cast<double>(n));
}

/// Mean Stokes of a render pair's average over a region, with standard errors from the pair's
/// per-pixel differences: Var((a + b)/2) = Var(a − b)/4 for independent seeds.
struct RegionStokes {
    std::size_t pixels = 0;
    double s0 = 0.0, s0_se = 0.0;               ///< mean S0, W/(m²·sr)
    std::array<double, 3> ratio{}, ratio_se{};  ///< ΣS1/ΣS0, ΣS2/ΣS0, ΣS3/ΣS0 (delta method)
};

RegionStokes region_stokes(const RenderPair& p, const std::vector<bool>& region) {
    RegionStokes r;
    std::array<double, 4> sum{};
    for (std::size_t i = 0; i < region.size(); ++i) {
        if (!region[i]) continue;
        for (std::size_t c = 0; c < 4; ++c)
            sum[c] +=
                0.5 * (p.a.channel(kStokesChannels[c])[i] + p.b.channel(kStokesChannels[c])[i]);
        ++r.pixels;
    }
    for (std::size_t c = 1; c < 4; ++c) r.ratio[c - 1] = sum[c] / sum[0];
    std::array<double, 4> var{};  // of the region sums
    for (std::size_t i = 0; i < region.size(); ++i) {
        if (!region[i]) continue;
        const double d0 = p.a.channel("S0")[i] - p.b.channel("S0")[i];
        var[0] += 0.25 * d0 * d0;
        for (std::size_t c = 1; c < 4; ++c) {
            const double d = p.a.channel(kStokesChannels[c])[i] -
                             p.b.channel(kStokesChannels[c])[i] - r.ratio[c - 1] * d0;
            var[c] += 0.25 * d * d;
        }
    }
    const auto n = static_cast<double>(r.pixels);
    r.s0 = sum[0] / n;
    r.s0_se = std::sqrt(var[0]) / n;
    for (std::size_t c = 1; c < 4; ++c) r.ratio_se[c - 1] = std::sqrt(var[c]) / sum[0];
    return r;
}

/// Worst disagreement between the two renderers over all regions.
struct Agreement {
    double max_abs_z = 0.0;  ///< of S0, S1/S0, S2/S0, S3/S0, difference over its standard error
    double max_relative_ds0 = 0.0;      ///< |ΔS0| / S0
    double max_ratio_difference = 0.0;  ///< |Δ(Sk/S0)|, k = 1..3
};

/// Prints, per object and image half, the means of both renderers with the z of their difference.
Agreement check_agreement(const Scene& scene, const RenderPair& tirpol, const RenderPair& mitsuba) {
    const Image& ids = tirpol.a;  // object hit by each pixel's centre ray (−1: sky)
    Agreement worst;
    std::printf(
        "Agreement per region: tirpol | Mitsuba (in tirpol's frame) (z = difference / its standard "
        "error)\n");
    for (std::size_t object = 0; object < scene.objects.size(); ++object)
        for (const bool right : {false, true}) {
            std::vector<bool> region(ids.pixel_count());
            for (int y = 0; y < ids.height(); ++y)
                for (int x = 0; x < ids.width(); ++x) {
                    const std::size_t i = ids.index(x, y);
                    region[i] = ids.channel("object_id")[i] == static_cast<float>(object) &&
                                (2 * x >= ids.width()) == right;
                }
            const RegionStokes t = region_stokes(tirpol, region),
                               m = region_stokes(mitsuba, region);
            if (t.pixels == 0) continue;
            const double z0 = (m.s0 - t.s0) / std::hypot(m.s0_se, t.s0_se);
            std::printf("  %-8s %-5s %6zu px  S0 %.4f | %.4f (z %+.1f)",
                        scene.objects[object].name.c_str(), right ? "right" : "left", t.pixels,
                        t.s0, m.s0, z0);
            worst.max_abs_z = std::max(worst.max_abs_z, std::abs(z0));
            worst.max_relative_ds0 = std::max(worst.max_relative_ds0, std::abs(m.s0 - t.s0) / t.s0);
            for (std::size_t k = 0; k < 3; ++k) {
                const double d = m.ratio[k] - t.ratio[k],
                             z = d / std::hypot(m.ratio_se[k], t.ratio_se[k]);
                std::printf("  S%zu/S0 %+.4f | %+.4f (z %+.1f)", k + 1, t.ratio[k], m.ratio[k], z);
                worst.max_abs_z = std::max(worst.max_abs_z, std::abs(z));
                worst.max_ratio_difference = std::max(worst.max_ratio_difference, std::abs(d));
            }
            std::printf("\n");
        }
    return worst;
}

/// Writes Mitsuba 3's version of reflection_compare.yaml and its envmap of the scene's sky.
/// Mitsuba's envmap is a lat-long image, y-up (rotated here to tirpol's z-up), whose row r lies at
/// zenith angle π·r/(rows − 1) (emitters/envmap.cpp: rows are samples from pole to pole, not pixel
/// centres). `sampler` is the Mitsuba sampler plugin (independent, stratified, multijitter,
/// orthogonal, ldsampler); Mitsuba rounds sample counts that a sampler cannot take (stratified: a
/// square; orthogonal: a prime squared), which does not matter here since times are interpolated
/// against the measured noise.
std::filesystem::path write_mitsuba_scene(const std::filesystem::path& dir, const Scene& scene,
                                          const std::string& sampler) {
    const int w = 256, h = 129;
    Image env(w, h);
    for (const char* c : {"R", "G", "B"}) env.add_channel(c);
    for (int y = 0; y < h; ++y) {
        const double theta = kPi * y / (h - 1);
        // Sky radiance at this zenith angle as tirpol sees it, integrated over the band.
        const Vec3 d(std::sin(theta), 0.0, std::cos(theta));
        double l = 0.0;
        for (const auto& node : scene.band.nodes())
            l += node.weight_um * scene.sky.spectral_radiance(node.wavelength_um, d);
        for (int x = 0; x < w; ++x)
            for (const char* c : {"R", "G", "B"})
                env.channel(c)[env.index(x, y)] = static_cast<float>(l);
    }
    write_exr(dir / "sky.exr", env);
    std::ofstream xml(dir / "scene.xml");
    xml << R"(<scene version="3.0.0">
  <default name="spp" value="16"/>
  <default name="seed" value="0"/>
  <integrator type="stokes"><integrator type="path"><integer name="max_depth" value="9"/></integrator></integrator>
  <sensor type="perspective">
    <float name="fov" value="40"/><string name="fov_axis" value="x"/>
    <transform name="to_world"><lookat origin="0, -5, 1.5" target="0, 0, 0.6" up="0, 0, 1"/></transform>
    <sampler type=")"
        << sampler
        << R"("><integer name="sample_count" value="$spp"/><integer name="seed" value="$seed"/></sampler>
    <film type="hdrfilm"><integer name="width" value="320"/><integer name="height" value="256"/>
      <string name="component_format" value="float32"/><rfilter type="box"/></film>
  </sensor>
  <emitter type="envmap"><string name="filename" value="sky.exr"/>
    <transform name="to_world"><rotate x="1" angle="90"/></transform></emitter>
  <shape type="rectangle">
    <transform name="to_world"><scale value="10"/></transform>
    <bsdf type="roughconductor"><string name="distribution" value="beckmann"/><float name="alpha" value="0.28284"/>
      <spectrum name="eta" value="1.5"/><spectrum name="k" value="0.05"/></bsdf>
  </shape>
  <shape type="sphere"><point name="center" value="0, 0, 0.6"/><float name="radius" value="0.6"/>
    <bsdf type="conductor"><spectrum name="eta" value="1.5"/><spectrum name="k" value="0.05"/></bsdf>
  </shape>
</scene>
)";
    return dir / "scene.xml";
}

/// One renderer's runs at doubling spp until the relative noise falls to the target.
struct NoiseRun {
    int spp = 0;
    double noise = 0.0, seconds = 0.0, cpu_seconds = 0.0;
};

/// Seconds (wall, CPU) to `target` noise, interpolated in log-log between the two runs that bracket
/// it (the last run is at or below the target, the one before above it); no 1/√N extrapolation.
std::pair<double, double> bracketed_seconds(const std::vector<NoiseRun>& runs, double target) {
    if (runs.size() < 2 || runs.back().noise > target || runs[runs.size() - 2].noise <= target)
        throw Error("no pair of runs brackets the target noise");
    const NoiseRun &lo = runs[runs.size() - 2], &hi = runs.back();
    const double f = std::log(target / lo.noise) / std::log(hi.noise / lo.noise);
    const auto interpolate = [f](double a, double b) {
        return std::exp(std::log(a) + f * (std::log(b) - std::log(a)));
    };
    return {interpolate(lo.seconds, hi.seconds), interpolate(lo.cpu_seconds, hi.cpu_seconds)};
}

/// Seconds of Mitsuba's "Rendering finished. (took 2.3456s)" log line (util::time_string's
/// ms/s/m/h).
double mitsuba_render_seconds(const std::filesystem::path& log_path) {
    std::ifstream log(log_path);
    const std::string key = "Rendering finished. (took ";
    for (std::string line; std::getline(log, line);) {
        const auto at = line.find(key);
        if (at == std::string::npos) continue;
        std::size_t end = 0;
        const std::string rest = line.substr(at + key.size());
        const double value = std::stod(rest, &end);
        const std::string unit = rest.substr(end, rest.find(')') - end);
        const double scale = unit == "ms"  ? 1e-3
                             : unit == "s" ? 1.0
                             : unit == "m" ? 60.0
                             : unit == "h" ? 3600.0
                                           : -1.0;
        if (scale > 0.0) return value * scale;
    }
    throw Error(log_path.string() +
                ": no \"Rendering finished. (took …)\" line with a time in ms, s, m or h");
}

/// The sample count Mitsuba rendered for `requested`: its samplers round counts they cannot take
/// up (stratified: a square; multijitter: a near-square product; orthogonal: a prime squared;
/// ldsampler: a power of four) and log it at warning level as "rounding to N" or "rounded up to N"
/// (samplers/*.cpp, v3.8.0); without such a line the count is the one requested.
int mitsuba_sample_count(const std::filesystem::path& log_path, int requested) {
    std::ifstream log(log_path);
    for (std::string line; std::getline(log, line);)
        for (const std::string key : {"rounding to ", "rounded up to "}) {
            const auto at = line.find(key);
            if (at == std::string::npos) continue;
            const int count = std::atoi(line.c_str() + at + key.size());
            if (count < requested)
                throw Error(log_path.string() + ": Mitsuba's sample count " +
                            std::to_string(count) + " is below the " + std::to_string(requested) +
                            " requested; expected it rounded up: \"" + line + "\"");
            return count;
        }
    return requested;
}

/// Mitsuba's Stokes AOVs (stokes integrator, mono: S0.R = S0.G = S0.B), re-expressed per pixel from
/// Mitsuba's frame (x = ray.d × camera-up) to tirpol's (camera-right projected onto the wavefront),
/// both for the pixel's centre ray.
Image in_tirpol_frame(const Image& mitsuba, const PinholeCamera& camera) {
    Image out(mitsuba.width(), mitsuba.height());
    for (const auto& c : kStokesChannels) out.set_channel(c, mitsuba.channel(c + ".R"));
    const Vec3 up = -camera.world_from_camera().col(1);  // camera axes: x right, y down, z forward
    for (int y = 0; y < out.height(); ++y)
        for (int x = 0; x < out.width(); ++x) {
            const Vec3 d = camera.ray_direction(x + 0.5, y + 0.5);
            const StokesFrame from{-d, d.cross(up).normalized()};
            const std::size_t i = out.index(x, y);
            float &s1 = out.channel("S1")[i], &s2 = out.channel("S2")[i];
            const StokesVector s =
                change_frame(StokesVector(out.channel("S0")[i], s1, s2, out.channel("S3")[i]), from,
                             camera.image_frame(d));
            s1 = static_cast<float>(s[1]);
            s2 = static_cast<float>(s[2]);
        }
    return out;
}

/// CPU seconds (user + system) of the waited-for child processes so far.
double children_cpu_seconds() {
    rusage usage{};
    getrusage(RUSAGE_CHILDREN, &usage);
    const auto seconds = [](const timeval& t) {
        return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec);
    };
    return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

/// Two Mitsuba 3 renders of `xml` (seeds 1 and 2) with `threads` threads. seconds is Mitsuba's own
/// render time (its log), without its start-up and scene loading, as tirpol's is without its own;
/// cpu_seconds is the whole process's (start-up, ~0.05 s, included); samples_per_pixel is the count
/// its sampler rendered.
RenderPair render_mitsuba(const std::string& executable, const std::filesystem::path& xml, int spp,
                          int threads, const PinholeCamera& camera) {
    RenderPair pair;
    for (const int seed : {1, 2}) {
        const auto out = xml.parent_path() / ("out" + std::to_string(seed) + ".exr");
        const auto log = xml.parent_path() / ("out" + std::to_string(seed) + ".log");
        const std::string command = "'" + executable + "' -m scalar_mono_polarized -t " +
                                    std::to_string(threads) + " -D spp=" + std::to_string(spp) +
                                    " -D seed=" + std::to_string(seed) + " -o '" + out.string() +
                                    "' '" + xml.string() + "' > '" + log.string() + "' 2>&1";
        const double cpu_before = children_cpu_seconds();
        if (std::system(command.c_str()) != 0)
            throw Error("Mitsuba 3 failed (log: " + log.string() + "): " + command);
        pair.cpu_seconds += 0.5 * (children_cpu_seconds() - cpu_before);
        pair.seconds += 0.5 * mitsuba_render_seconds(log);
        pair.samples_per_pixel = mitsuba_sample_count(log, spp);
        (seed == 1 ? pair.a : pair.b) = in_tirpol_frame(read_exr(out), camera);
    }
    return pair;
}

constexpr double kTargetNoise = 0.01;  // relative S1/S2 noise both renderers are run to
constexpr int kMaxBracketSpp = 1 << 14;

const std::vector<std::string> kMitsubaSamplers = {"independent", "stratified", "multijitter",
                                                   "orthogonal", "ldsampler"};

/// The Mitsuba samplers to compare: TIRPOL_MITSUBA_SAMPLERS, comma-separated names from
/// kMitsubaSamplers (to spend a loaded machine's time on some of them), else all.
std::vector<std::string> mitsuba_samplers() {
    const char* list = std::getenv("TIRPOL_MITSUBA_SAMPLERS");
    if (!list || !*list) return kMitsubaSamplers;
    std::vector<std::string> chosen;
    std::string rest = list;
    while (!rest.empty()) {
        const auto comma = rest.find(',');
        const std::string name = rest.substr(0, comma);
        rest = comma == std::string::npos ? "" : rest.substr(comma + 1);
        if (std::find(kMitsubaSamplers.begin(), kMitsubaSamplers.end(), name) ==
            kMitsubaSamplers.end())
            throw Error("TIRPOL_MITSUBA_SAMPLERS: unknown sampler \"" + name +
                        "\"; expected comma-separated names from independent, stratified, "
                        "multijitter, orthogonal, ldsampler");
        chosen.push_back(name);
    }
    return chosen;
}

// The two renderers' means may differ by their documented model differences (Mitsuba's uncorrelated
// Smith G on the rough plane: −1 % in S0 at grazing rows, −0.4 % over the plane); a mistranslated
// scene (sky, index, geometry, frames) differs by far more, and then no ratio is reported.
constexpr double kMaxRelativeS0Difference = 0.01;
constexpr double kMaxRatioDifference = 0.005;

void BM_ReflectionEqualNoise(benchmark::State& state) {
    const int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    Scene scene = load_scene(find_config("scenes/reflection_compare.yaml"));
    RenderOptions options;
    options.threads = threads;
    std::vector<bool> mask;
    std::vector<NoiseRun> tirpol_runs;
    RenderPair tirpol;  // the last run: its means are the ones compared with Mitsuba's
    for (auto _ : state) {
        tirpol_runs.clear();
        for (int spp = 16; spp <= kMaxBracketSpp; spp *= 2) {
            RenderStatistics sa, sb;
            scene.sampling.samples_per_pixel = spp;
            scene.sampling.seed = 1;
            tirpol.a = render(scene, options, &sa);
            scene.sampling.seed = 2;
            tirpol.b = render(scene, options, &sb);
            if (mask.empty()) {
                mask.resize(tirpol.a.pixel_count());
                for (std::size_t i = 0; i < mask.size(); ++i)
                    mask[i] = tirpol.a.channel("object_id")[i] >= 0.0f;
            }
            tirpol.seconds = 0.5 * (sa.seconds - sa.setup_seconds + sb.seconds - sb.setup_seconds);
            tirpol.cpu_seconds = 0.5 * (sa.trace_cpu_seconds + sb.trace_cpu_seconds);
            tirpol_runs.push_back(
                {spp, relative_linear_noise(tirpol, mask), tirpol.seconds, tirpol.cpu_seconds});
            std::printf(
                "tirpol %5d spp, %d threads: %.2f s per render (%.2f CPU s), relative S1/S2 noise "
                "%.4f\n",
                spp, threads, tirpol.seconds, tirpol.cpu_seconds, tirpol_runs.back().noise);
            if (tirpol_runs.back().noise <= kTargetNoise) break;
        }
        state.SetIterationTime(tirpol.seconds);
    }
    if (tirpol_runs.size() < 2) {  // 16 spp already below 1 %: no bracket from above
        state.SkipWithError("tirpol's first run is already below the target noise: start lower");
        return;
    }
    const auto [tirpol_s, tirpol_cpu_s] = bracketed_seconds(tirpol_runs, kTargetNoise);
    state.counters["threads"] = threads;
    state.counters["tirpol_equal_noise_s"] = tirpol_s;
    state.counters["tirpol_equal_noise_cpu_s"] = tirpol_cpu_s;
    std::printf("tirpol to 1 %% (log-log between %d and %d spp): %.2f s wall, %.2f CPU s\n",
                tirpol_runs[tirpol_runs.size() - 2].spp, tirpol_runs.back().spp, tirpol_s,
                tirpol_cpu_s);

    const char* mitsuba = std::getenv("TIRPOL_MITSUBA");
    if (!mitsuba || !*mitsuba) {
        std::printf(
            "Mitsuba 3 comparison: skipped (set TIRPOL_MITSUBA to a mitsuba executable built with "
            "scalar_mono_polarized; docs/simulation.md)\n");
        return;
    }
    const auto dir = std::filesystem::temp_directory_path() / "tirpol_mitsuba_bench";
    std::filesystem::create_directories(dir);
    double best_cpu_s = std::numeric_limits<double>::infinity();
    std::string best;
    Agreement worst;  // over the samplers
    std::vector<std::string> samplers;
    try {
        samplers = mitsuba_samplers();
    } catch (const Error& e) {
        state.SkipWithError(e.what());
        return;
    }
    for (const std::string& sampler : samplers) {
        std::vector<NoiseRun> runs;
        RenderPair other;
        try {
            const auto xml = write_mitsuba_scene(dir, scene, sampler);
            // Requests double, but past what the sampler rounded the last one up to, so that no
            // count is rendered twice (ldsampler: 32 becomes 64, and 64 would repeat it).
            for (int spp = 16; spp <= kMaxBracketSpp;
                 spp = std::max(2 * spp, other.samples_per_pixel + 1)) {
                other = render_mitsuba(mitsuba, xml, spp, threads, scene.camera);
                runs.push_back({other.samples_per_pixel, relative_linear_noise(other, mask),
                                other.seconds, other.cpu_seconds});
                std::printf(
                    "Mitsuba %-11s %5d spp (%5d asked): %.2f s per render (%.2f CPU s), relative "
                    "noise %.4f\n",
                    sampler.c_str(), other.samples_per_pixel, spp, other.seconds, other.cpu_seconds,
                    runs.back().noise);
                if (runs.back().noise <= kTargetNoise) break;
            }
            const Agreement agreement = check_agreement(scene, tirpol, other);
            worst.max_abs_z = std::max(worst.max_abs_z, agreement.max_abs_z);
            worst.max_relative_ds0 = std::max(worst.max_relative_ds0, agreement.max_relative_ds0);
            worst.max_ratio_difference =
                std::max(worst.max_ratio_difference, agreement.max_ratio_difference);
            state.counters["agree_max_abs_z"] = worst.max_abs_z;
            state.counters["agree_max_rel_dS0"] = worst.max_relative_ds0;
            state.counters["agree_max_d_ratio"] = worst.max_ratio_difference;
            if (agreement.max_relative_ds0 > kMaxRelativeS0Difference ||
                agreement.max_ratio_difference > kMaxRatioDifference) {
                state.SkipWithError(
                    "tirpol and Mitsuba 3 disagree on the means (table above): different scenes, "
                    "no ratio");
                return;
            }
            const auto [other_s, other_cpu_s] = bracketed_seconds(runs, kTargetNoise);
            std::printf(
                "Mitsuba %-11s to 1 %% (log-log between %d and %d spp): %.2f s wall, %.2f CPU s; "
                "tirpol/Mitsuba %.2f (wall), %.2f (CPU)\n",
                sampler.c_str(), runs[runs.size() - 2].spp, runs.back().spp, other_s, other_cpu_s,
                tirpol_s / other_s, tirpol_cpu_s / other_cpu_s);
            state.counters["tirpol_over_" + sampler + "_cpu"] = tirpol_cpu_s / other_cpu_s;
            if (other_cpu_s < best_cpu_s) {
                best_cpu_s = other_cpu_s;
                best = sampler;
            }
        } catch (const Error& e) {
            state.SkipWithError(e.what());
            return;
        }
    }
    state.counters["tirpol_over_best_mitsuba_cpu"] = tirpol_cpu_s / best_cpu_s;
    std::printf("tirpol/Mitsuba (best sampler: %s) equal-noise CPU time ratio at 1 %%: %.2f\n",
                best.c_str(), tirpol_cpu_s / best_cpu_s);
}
BENCHMARK(BM_ReflectionEqualNoise)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);

// ---- VarianceCalibration and ConvergenceExponent: the sampler's error bars and convergence ----

/// Σ(a − b)² / Σ(var_a + var_b) of channel `c` over the pixels of `material` (material_id), pooled
/// over render pairs with different seeds (1 where the variance channels are unbiased), and its
/// standard error √Σ(dᵢ² − r·vᵢ)² / Σvᵢ (delta method over the pixels).
struct TwoSeedRatio {
    double ratio = 0.0, standard_error = 0.0;
    std::size_t values = 0, beyond5 = 0;  ///< |z| = |a − b|/√(var_a + var_b) > 5
};

TwoSeedRatio two_seed_ratio(const std::vector<std::pair<Image, Image>>& pairs, const std::string& c,
                            float material) {
    std::vector<double> d2, v;
    for (const auto& [a, b] : pairs)
        for (std::size_t i = 0; i < a.pixel_count(); ++i) {
            if (a.channel("material_id")[i] != material) continue;
            const double d = static_cast<double>(a.channel(c)[i]) - b.channel(c)[i];
            d2.push_back(d * d);
            v.push_back(static_cast<double>(a.channel(c + "_var")[i]) + b.channel(c + "_var")[i]);
        }
    TwoSeedRatio out;
    const double sum_d2 = std::accumulate(d2.begin(), d2.end(), 0.0),
                 sum_v = std::accumulate(v.begin(), v.end(), 0.0);
    out.ratio = sum_d2 / sum_v;
    double spread = 0.0;
    for (std::size_t i = 0; i < d2.size(); ++i) {
        spread += std::pow(d2[i] - out.ratio * v[i], 2);
        out.beyond5 += d2[i] > 25.0 * v[i] ? 1 : 0;
    }
    out.standard_error = std::sqrt(spread) / sum_v;
    out.values = d2.size();
    return out;
}

/// Per material region (≥ 500 pixels) of panels_night, ball_on_snow_night and vehicles_night at
/// their own 320×256, at 8, 32 and 128 spp, both estimators, two seed pairs: the two-seed ratio of
/// S0, S1, S2 with its standard error, the share of |z| beyond 5, and over the regions χ²/n of (r −
/// 1)/se (1 when the ratios scatter about 1 as their errors say). Figures, not speed.
void BM_VarianceCalibration(benchmark::State& state) {
    for (auto _ : state) {
        for (const char* name : {"panels_night", "ball_on_snow_night", "vehicles_night"}) {
            Scene scene = load_scene(find_config(std::string("scenes/") + name + ".yaml"));
            for (const int spp : {8, 32, 128})
                for (const bool cv : {false, true}) {
                    RenderOptions options;
                    options.control_variate = cv;
                    scene.sampling.samples_per_pixel = spp;
                    std::vector<std::pair<Image, Image>> pairs;
                    for (const std::uint64_t seed : {1, 3}) {
                        scene.sampling.seed = seed;
                        Image a = render(scene, options);
                        scene.sampling.seed = seed + 1;
                        pairs.emplace_back(std::move(a), render(scene, options));
                    }
                    double chi2 = 0.0, lowest = 1e9, highest = 0.0;
                    std::size_t ratios = 0, values = 0, beyond5 = 0;
                    for (std::size_t m = 0; m < scene.materials.size(); ++m) {
                        const auto id = static_cast<float>(m);
                        const auto& ids = pairs.front().first.channel("material_id");
                        const auto pixels =
                            static_cast<std::size_t>(std::count(ids.begin(), ids.end(), id));
                        if (pixels < 500) continue;
                        std::string line;
                        for (const char* c : {"S0", "S1", "S2"}) {
                            const TwoSeedRatio r = two_seed_ratio(pairs, c, id);
                            line +=
                                fmt::format(" {} {:.3f} ± {:.3f}", c, r.ratio, r.standard_error);
                            chi2 += std::pow((r.ratio - 1.0) / r.standard_error, 2);
                            lowest = std::min(lowest, r.ratio);
                            highest = std::max(highest, r.ratio);
                            ++ratios;
                            values += r.values;
                            beyond5 += r.beyond5;
                        }
                        std::printf("%-19s %3d spp %-15s %-24s %5zu px:%s\n", name, spp,
                                    cv ? "control-variate" : "plain",
                                    scene.materials[m].name.c_str(), pixels, line.c_str());
                    }
                    std::printf(
                        "%-19s %3d spp %-15s all regions: ratios %.2f–%.2f, χ²/n of (r − 1)/se "
                        "%.2f (n = %zu), "
                        "|z| > 5 in %.4f %% of %zu values\n",
                        name, spp, cv ? "control-variate" : "plain", lowest, highest, chi2 / ratios,
                        ratios, 100.0 * static_cast<double>(beyond5) / values, values);
                }
        }
        state.SetIterationTime(1.0);
    }
}
BENCHMARK(BM_VarianceCalibration)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);

/// What the replicate count costs: relative S1/S2 and S0 noise (two seeds, surface pixels) at 64
/// and 256 spp with R = 1, 4, 8, 16, 32 replicates, on reflection_compare and panels_night at
/// 160×128. Fewer replicates keep more of the sequence's stratification (lower noise) but give the
/// variance R − 1 degrees of freedom. Figures, not speed.
void BM_ReplicateCount(benchmark::State& state) {
    for (auto _ : state) {
        for (const char* name : {"reflection_compare", "panels_night"}) {
            Scene scene = load_scene(find_config(std::string("scenes/") + name + ".yaml"));
            scene.camera = scene.camera.resized(160, 128);
            for (const int spp : {64, 256})
                for (const int replicates : {1, 4, 8, 16, 32}) {
                    scene.sampling.samples_per_pixel = spp;
                    scene.sampling.replicates = replicates;
                    RenderPair pair;
                    scene.sampling.seed = 1;
                    pair.a = render(scene);
                    scene.sampling.seed = 2;
                    pair.b = render(scene);
                    std::vector<bool> mask(pair.a.pixel_count());
                    double d0 = 0.0, s0 = 0.0;
                    std::size_t n = 0;
                    for (std::size_t i = 0; i < mask.size(); ++i) {
                        mask[i] = pair.a.channel("object_id")[i] >= 0.0f;
                        if (!mask[i]) continue;
                        d0 += 0.5 * std::pow(pair.a.channel("S0")[i] - pair.b.channel("S0")[i], 2);
                        s0 += pair.a.channel("S0")[i];
                        ++n;
                    }
                    std::printf(
                        "%-18s 160x128 %3d spp, R = %2d: relative noise S1/S2 %.5f, S0 %.6f\n",
                        name, spp, replicates, relative_linear_noise(pair, mask),
                        std::sqrt(d0 / n) / (s0 / n));
                }
        }
        state.SetIterationTime(1.0);
    }
}
BENCHMARK(BM_ReplicateCount)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);

/// Relative S1/S2 noise (two seeds, surface pixels) of `scene` at 16, 64 and 256 spp, the exponent
/// of a least-squares fit noise ∝ spp^a (goal ≤ −0.8), and the surfaces' two-seed variance ratio.
void convergence_exponent(Scene scene, const char* name) {
    std::vector<double> log_spp, log_noise;
    for (const int spp : {16, 64, 256}) {
        scene.sampling.samples_per_pixel = spp;
        RenderPair pair;
        RenderStatistics stats;
        scene.sampling.seed = 1;
        pair.a = render(scene, {}, &stats);
        scene.sampling.seed = 2;
        pair.b = render(scene);
        std::vector<bool> mask(pair.a.pixel_count());
        double diff = 0.0, var = 0.0;
        for (std::size_t i = 0; i < mask.size(); ++i) {
            mask[i] = pair.a.channel("object_id")[i] >= 0.0f;
            if (!mask[i]) continue;
            for (const char* c : {"S1", "S2"}) {
                const double d = pair.a.channel(c)[i] - pair.b.channel(c)[i];
                diff += d * d;
                var += pair.a.channel(std::string(c) + "_var")[i] +
                       pair.b.channel(std::string(c) + "_var")[i];
            }
        }
        const double noise = relative_linear_noise(pair, mask);
        log_spp.push_back(std::log(spp));
        log_noise.push_back(std::log(noise));
        std::printf(
            "%s %d spp: relative S1/S2 noise %.5f, two-seed variance ratio %.3f, %.3f CPU s per "
            "render\n",
            name, spp, noise, diff / var, stats.trace_cpu_seconds);
    }
    const double mx = std::accumulate(log_spp.begin(), log_spp.end(), 0.0) / 3.0;
    const double my = std::accumulate(log_noise.begin(), log_noise.end(), 0.0) / 3.0;
    double sxy = 0.0, sxx = 0.0;
    for (std::size_t k = 0; k < 3; ++k) {
        sxy += (log_spp[k] - mx) * (log_noise[k] - my);
        sxx += (log_spp[k] - mx) * (log_spp[k] - mx);
    }
    std::printf("%s: noise ∝ spp^%.3f (16 -> 256 spp; goal ≤ −0.8)\n", name, sxy / sxx);
}

void BM_ConvergenceExponent(benchmark::State& state) {
    for (auto _ : state) {
        convergence_exponent(load_scene(find_config("scenes/reflection_compare.yaml")),
                             "reflection_compare 320x256");
        Scene panels = load_scene(find_config("scenes/panels_night.yaml"));
        panels.camera = panels.camera.resized(160, 128);
        convergence_exponent(panels, "panels_night 160x128");
        state.SetIterationTime(1.0);
    }
}
BENCHMARK(BM_ConvergenceExponent)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
