// A standalone thermal scene simulated to one time (`tirpol therm`): the shipped ball-on-snow
// example at noon shows the paper's Fig. 2 ordering, keeping the 24-hour history changes only what
// is recorded (the final state is the same), and the CSV and JSON report every object once.

#include <gtest/gtest.h>

#include <map>
#include <sstream>

#include "test_support.h"
#include "tirpol/core/error.h"
#include "tirpol/thermal/civil_time.h"
#include "tirpol/thermal/thermal_config.h"

namespace tirpol::thermal {
namespace {

ThermalScene ball_on_snow() {
    return load_thermal_scene(test::source_dir() / "config/thermal/ball_on_snow_thermal.yaml");
}

double noon(const ThermalScene& scene) {
    return parse_time("2026-01-16T12:00", scene.site.utc_offset_h, "test");
}

TEST(ThermalRun, BallOnSnowAtNoonOrdersSurfacesAsThePaperFigure2) {
    const ThermalScene scene = ball_on_snow();
    const ThermalRun run = simulate_thermal_scene(scene, noon(scene), false);
    ASSERT_EQ(run.objects.size(), scene.objects.size());
    std::map<std::string, double> t;
    for (const auto& o : run.objects) {
        ASSERT_EQ(o.samples.size(), 1u) << o.object->name;
        EXPECT_EQ(o.samples.back().time_s, noon(scene));
        t[o.object->name] = o.samples.back().surface_temperature_k;
    }
    EXPECT_GT(t.at("ball_top"), t.at("snow_field"));             // ball warmer than snow by day
    EXPECT_GT(t.at("ball_south"), t.at("ball_north"));           // sunlit side warmer
    EXPECT_GT(t.at("snow_field"), t.at("snow_in_ball_shadow"));  // shadow is colder
}

TEST(ThermalRun, HistoryKeepsTheLast24HoursAndTheSameFinalState) {
    const ThermalScene scene = ball_on_snow();
    const ThermalRun once = simulate_thermal_scene(scene, noon(scene), false);
    const ThermalRun day = simulate_thermal_scene(scene, noon(scene), true);
    ASSERT_EQ(day.objects.size(), once.objects.size());
    for (std::size_t k = 0; k < day.objects.size(); ++k) {
        const auto& samples = day.objects[k].samples;
        ASSERT_EQ(samples.size(), 24u * 4u + 1u);  // every 15 min over 24 h, both ends
        EXPECT_EQ(samples.front().time_s, noon(scene) - 24 * 3600.0);
        EXPECT_NEAR(samples.back().surface_temperature_k,
                    once.objects[k].samples.back().surface_temperature_k, 0.05)
            << day.objects[k].object->name;
    }
}

TEST(ThermalRun, CsvAndJsonReportEveryObjectOnce) {
    const ThermalScene scene = ball_on_snow();
    const ThermalRun run = simulate_thermal_scene(scene, noon(scene), false);
    std::istringstream csv(thermal_run_csv(scene, run));
    std::string line;
    std::getline(csv, line);
    EXPECT_EQ(line.rfind("object,material,tilt_deg,azimuth_deg,shadow_fraction,temperature_k", 0),
              0u);
    std::size_t rows = 0;
    while (std::getline(csv, line)) {
        EXPECT_EQ(line.rfind(run.objects[rows].object->name + ",", 0), 0u) << line;
        ++rows;
    }
    EXPECT_EQ(rows, scene.objects.size());
    const nlohmann::json j = thermal_run_json(scene, run);
    EXPECT_EQ(j["time"], "2026-01-16T12:00:00-05:00");
    ASSERT_EQ(j["objects"].size(), scene.objects.size());
    EXPECT_EQ(j["objects"][0]["temperature_k"].get<double>(),
              run.objects[0].samples.back().surface_temperature_k);
}

TEST(ThermalRun, ATimeTheWeatherDoesNotCoverIsAnError) {
    const ThermalScene scene = ball_on_snow();
    EXPECT_THROW(simulate_thermal_scene(scene, parse_time("2030-01-01T00:00", 0.0, "test"), false),
                 Error);
}

}  // namespace
}  // namespace tirpol::thermal
