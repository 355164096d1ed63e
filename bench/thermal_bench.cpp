// Thermal model cost: a 24-hour spin-up for 100 material × orientation facets, against references
// measured in the same run (one SPA evaluation, one implicit step of a 40-cell slab) so the figures
// read as ratios. The cost added to a render is this spin-up per distinct (material, orientation).

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <cmath>
#include <filesystem>

#include "tirpol/core/source_tree.h"
#include "tirpol/simulation/renderer.h"
#include "tirpol/simulation/scene.h"
#include "tirpol/thermal/civil_time.h"
#include "tirpol/thermal/solar_position.h"
#include "tirpol/thermal/surface_temperature.h"

namespace {
using namespace tirpol;
using namespace tirpol::thermal;

const Site kSite{"bench", 43.16, -77.61, -5.0, 169.0};

WeatherSeries two_clear_days() {
    std::vector<WeatherRecord> records;
    const double t0 = parse_time("2026-01-15T00:00", kSite.utc_offset_h);
    for (int h = 0; h <= 48; ++h) {
        WeatherRecord r;
        r.time_s = t0 + h * 3600.0;
        r.air_temperature_c = -5.0 + 4.0 * std::sin(2.0 * kPi * (h % 24 - 9) / 24.0);
        r.dew_point_c = -14.0;
        r.relative_humidity_pct = 50.0;
        r.pressure_pa = 99300.0;
        r.wind_speed_m_s = 2.0;
        const double cz = std::max(0.0, std::sin(2.0 * kPi * (h % 24 - 7.5) / 19.0));
        r.direct_normal_w_m2 = h % 24 > 7 && h % 24 < 17 ? 700.0 * std::pow(cz, 0.25) : 0.0;
        r.diffuse_horizontal_w_m2 = 60.0 * cz;
        r.global_horizontal_w_m2 = r.diffuse_horizontal_w_m2 + 0.4 * r.direct_normal_w_m2;
        r.opaque_sky_cover_tenths = 0.0;
        records.push_back(r);
    }
    return WeatherSeries(kSite, records, "bench", 0.0);
}

ThermalMaterial material(int i) {
    ThermalMaterial m;
    m.name = fmt::format("m{}", i);
    // 10 materials from a thin shell to a thick two-layer wall: 4 to 80 cells at 5 mm.
    m.slab.layers = {{0.004 + 0.02 * i, 0.2 + 0.15 * i, 1200.0 + 100.0 * i, 900.0 + 50.0 * i, 0}};
    if (i % 2) m.slab.layers.push_back({0.05, 0.04, 30.0, 1400.0, 0});
    m.solar_absorptivity = 0.3 + 0.06 * i;
    m.thermal_emissivity = 0.9;
    return m;
}

void BM_SolarPositionReference(benchmark::State& state) {
    SpaInput in;
    in.latitude_deg = kSite.latitude_deg;
    in.longitude_deg = kSite.longitude_deg;
    in.unix_seconds = parse_time("2026-01-16T12:00", kSite.utc_offset_h);
    for (auto _ : state) {
        benchmark::DoNotOptimize(solar_position(in).zenith_deg);
        in.unix_seconds += 1.0;
    }
}
BENCHMARK(BM_SolarPositionReference);

void BM_SlabStepReference(benchmark::State& state) {
    SlabDefinition def;
    def.layers = {{0.2, 1.4, 2300.0, 880.0, 40}};
    SlabModel slab(def);
    slab.set_uniform_temperature(280.0);
    SurfaceForcing f;
    f.emissivity = 0.9;
    f.incident_longwave_w_m2 = 250.0;
    f.air_temperature_k = 275.0;
    f.convection_w_m2_k = 10.0;
    for (auto _ : state) {
        f.absorbed_shortwave_w_m2 =
            f.absorbed_shortwave_w_m2 > 500.0 ? 0.0 : f.absorbed_shortwave_w_m2 + 1.0;
        benchmark::DoNotOptimize(slab.step(300.0, f, 1.0).newton_iterations);
    }
}
BENCHMARK(BM_SlabStepReference);

// 10 materials × 10 orientations = 100 facets, each spun up for 24 h at a 300 s step.
void BM_SpinUp24h_100Facets(benchmark::State& state) {
    const WeatherSeries weather = two_clear_days();
    const double at = parse_time("2026-01-16T13:00", kSite.utc_offset_h);
    ThermalOptions options;
    options.spin_up_hours = 24.0;
    long steps = 0;
    for (auto _ : state) {
        double sum = 0.0;
        for (int m = 0; m < 10; ++m) {
            const ThermalMaterial mat = material(m);
            for (int o = 0; o < 10; ++o) {
                const Facet facet{o < 2 ? 180.0 * o : 90.0, o < 2 ? 180.0 : 45.0 * (o - 2)};
                sum += predict_surface_temperature(weather, mat, facet, at, options);
                steps += static_cast<long>(24 * 3600 / options.time_step_s);
            }
        }
        benchmark::DoNotOptimize(sum);
    }
    state.counters["facet_steps_per_s"] =
        benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SpinUp24h_100Facets)->Unit(benchmark::kMillisecond);

// The same 100 facets stepped together: weather, sun and sky evaluated once per step.
void BM_SpinUp24h_100Facets_Batched(benchmark::State& state) {
    const WeatherSeries weather = two_clear_days();
    const double at = parse_time("2026-01-16T13:00", kSite.utc_offset_h);
    ThermalOptions options;
    options.spin_up_hours = 24.0;
    std::vector<ThermalMaterial> materials;
    for (int m = 0; m < 10; ++m) materials.push_back(material(m));
    std::vector<FacetRequest> requests;
    for (const auto& mat : materials)
        for (int o = 0; o < 10; ++o)
            requests.push_back(
                {&mat, Facet{o < 2 ? 180.0 * o : 90.0, o < 2 ? 180.0 : 45.0 * (o - 2)}, {}});
    long steps = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(
            predict_surface_temperatures(weather, requests, at, options).front());
        steps +=
            static_cast<long>(requests.size()) * static_cast<long>(24 * 3600 / options.time_step_s);
    }
    state.counters["facet_steps_per_s"] =
        benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SpinUp24h_100Facets_Batched)->Unit(benchmark::kMillisecond);

// The cost the thermal model adds to a render: loading the ball-on-snow day scene with predicted
// temperatures (1152-texel sphere map + mesh vertices, 24 h spin-up each) against loading the same
// scene and rendering it at 32×24, 2 spp (wall-clock: the renderer runs on all cores).
std::filesystem::path predicted_scene() {
    return find_config("thermal/ball_on_snow_day_predicted.yaml");
}

void BM_BallOnSnowSceneLoadWithPredictedTemperatures(benchmark::State& state) {
    const auto path = predicted_scene();
    for (auto _ : state) benchmark::DoNotOptimize(simulation::load_scene(path).objects.size());
}
BENCHMARK(BM_BallOnSnowSceneLoadWithPredictedTemperatures)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_BallOnSnowRender32x24x2spp(benchmark::State& state) {
    simulation::Scene scene = simulation::load_scene(predicted_scene());
    scene.camera = scene.camera.resized(32, 24);
    scene.sampling.samples_per_pixel = 2;
    for (auto _ : state) benchmark::DoNotOptimize(simulation::render(scene).width());
}
BENCHMARK(BM_BallOnSnowRender32x24x2spp)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
