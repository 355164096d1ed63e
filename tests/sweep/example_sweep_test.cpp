// The example sweep shipped in config/sweeps/ (the one docs/sweep.md is built around) runs as
// shipped and gives what the page says: 6 points (3 times of day × 2 paint roughnesses) with their
// polarizer images, table, plots and contact sheets, and the paper's day/night phenomenology of the
// ball on snow (§4, Figs. 2–3; time_of_day_test.cpp explains the physics): the radial S1 pattern of
// emission at every point, the ball solar-loaded and its pattern stronger at noon than at midnight,
// and weaker on the rougher paint (roughness mixes the emission's polarization planes).

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "sweep_test_support.h"
#include "tirpol/sweep/sweep_run.h"

namespace tirpol::sweep {
namespace {

const Estimate& value(const PointStatistics& s, const std::string& name,
                      const std::string& quantity_name) {
    for (std::size_t q = 0; q < std::size(kQuantityNames); ++q) {
        if (kQuantityNames[q] != quantity_name) continue;
        for (const auto& r : s.regions)
            if (r.name == name) return quantity(r.values, q);
        for (const auto& c : s.contrasts)
            if (c.name == name) return quantity(c.values, q);
    }
    throw std::runtime_error("no " + name + " " + quantity_name);
}

std::size_t line_count(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::size_t n = 0;
    for (std::string line; std::getline(in, line);) n += !line.empty();
    return n;
}

TEST(ExampleSweep, ShippedBallOnSnowDayRunsAndShowsTheDayNightChange) {
    tirpol::test::TempDir dir;
    const auto file = tirpol::test::source_dir() / "config/sweeps/ball_on_snow_day.yaml";
    const SweepSummary summary = run_sweep(load_sweep(file), dir / "out", {0, false, false});
    ASSERT_EQ(summary.points.size(), 6u);
    ASSERT_EQ(summary.rendered, 6u) << "failed: " << summary.failed;

    // Grid order, first axis slowest: points 0–1 at 00:00, 2–3 at 06:00, 4–5 at 12:00; even points
    // σ = 0.05, odd σ = 0.2.
    for (std::size_t i = 0; i < 6; ++i) {
        const PointStatistics& s = *summary.points[i].statistics;
        const Estimate& c = value(s, "s1_pattern", "S1");
        EXPECT_GT(c.mean, 3.0 * c.error) << "radial emission pattern at point " << i;
    }
    for (std::size_t roughness = 0; roughness < 2; ++roughness) {
        const PointStatistics& night = *summary.points[roughness].statistics;
        const PointStatistics& noon = *summary.points[4 + roughness].statistics;
        const double dt_night = value(night, "ball_vs_snow", "temperature_k").mean;
        const double dt_noon = value(noon, "ball_vs_snow", "temperature_k").mean;
        EXPECT_LT(std::abs(dt_night), 5.0) << "ball near the snow's temperature at night";
        EXPECT_GT(dt_noon, 20.0) << "solar-loaded ball at noon";
        const Estimate& c_night = value(night, "s1_pattern", "S1");
        const Estimate& c_noon = value(noon, "s1_pattern", "S1");
        EXPECT_GT(c_noon.mean - c_night.mean, 5.0 * std::hypot(c_noon.error, c_night.error))
            << "σ index " << roughness;
    }
    // Rougher paint depolarizes the ball's emission: a weaker pattern at every time.
    for (std::size_t t = 0; t < 3; ++t)
        EXPECT_LT(value(*summary.points[2 * t + 1].statistics, "s1_pattern", "S1").mean,
                  value(*summary.points[2 * t].statistics, "s1_pattern", "S1").mean)
            << "time index " << t;

    const auto out = dir / "out";
    EXPECT_EQ(line_count(out / "results.csv"), 7u) << "a header and one row per point";
    for (const char* f : {"manifest.json", "results.json", "plots/time_S1.png",
                          "contact_sheet_S0.png", "contact_sheet_S1.png", "animation/index.html"})
        EXPECT_TRUE(std::filesystem::is_regular_file(out / f)) << f;
    for (const char* f :
         {"stokes.exr", "statistics.json", "pol000.exr", "pol045.exr", "pol090.exr", "pol135.exr"})
        EXPECT_TRUE(std::filesystem::is_regular_file(out / "points/p0005" / f)) << f;
}

}  // namespace
}  // namespace tirpol::sweep
