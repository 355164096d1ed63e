// A time-of-day sweep of the paper's ball on snow (§4, Figs. 2 and 3) with temperatures, sun and
// sky predicted by the thermal model from the synthetic winter weather, at 02:00 (clear night) and
// 12:00 (sun ≈ 25° high), reproduces the paper's day/night change of the ball's S1 pattern.
//
// Physics (paper §2.3, eq 13): a surface's emitted radiance is polarized in its plane of emission,
// with a strength ∝ (ε_p − ε_s)·(L_bb(T_ball) − L_reflected), where L_reflected is what the ball
// reflects from the direction of specular reflection: the sky on its upper half, the snow on its
// lower half. On the ball's image this gives the radial pattern S1 > 0 at 3 and 9 o'clock, S1 < 0
// at 12 and 6 (conventions.md), so the pattern contrast C = mean S1(sides) − mean S1(top and
// bottom) is > 0.
// - Night: the ball is at about the snow's temperature ("roughly the same as the background"), so
// on its
//   lower half L_bb(T_ball) ≈ L_snow and the polarization cancels ("the polarization of the
//   thermally emitted radiance on the lower half of the ball is canceled out by the reflected
//   radiance coming from the ground"); the upper half still shows it, the ball being warmer than
//   the cold clear sky.
// - Day: solar loading makes the ball much warmer than the snow and the sky, so both halves are
//   polarized and C grows: with the lower half no longer cancelled alone C at least doubles.

#include <gtest/gtest.h>

#include <cmath>

#include "../apps/cli_runner.h"
#include "sweep_test_support.h"
#include "tirpol/sweep/sweep_run.h"

namespace tirpol::sweep {
namespace {

const Estimate& value(const PointStatistics& s, const std::string& region,
                      const char* quantity_name) {
    for (const auto& r : s.regions)
        if (r.name == region)
            for (std::size_t q = 0; q < std::size(kQuantityNames); ++q)
                if (std::string(kQuantityNames[q]) == quantity_name) return quantity(r.values, q);
    for (const auto& c : s.contrasts)
        if (c.name == region && std::string(quantity_name) == "S1") return c.values.s1;
    throw std::runtime_error("no " + region + " " + quantity_name);
}

TEST(SweepTimeOfDay, BallOnSnowS1PatternIsCancelledBelowAtNightAndStrongByDay) {
    tirpol::test::TempDir dir;
    tirpol::test::write_text(
        dir / "day.yaml",
        "scene: " +
            (tirpol::test::source_dir() / "config/thermal/ball_on_snow_day_predicted.yaml")
                .string() +
            R"(
axes:
  time: [2026-01-16T02:00, 2026-01-16T12:00]
regions:
  ball: {object: ball}
  snow: {object: snow}
  ball_top: {object: ball, sectors_deg: [[45, 135]]}
  ball_bottom: {object: ball, sectors_deg: [[225, 315]]}
  ball_sides: {object: ball, sectors_deg: [[-45, 45], [135, 225]]}
  ball_top_bottom: {object: ball, sectors_deg: [[45, 135], [225, 315]]}
contrasts:
  s1_pattern: {a: ball_sides, b: ball_top_bottom}
)");
    const SweepSummary summary =
        run_sweep(load_sweep(dir / "day.yaml"), dir / "out", {0, false, false});
    ASSERT_EQ(summary.rendered, 2u);
    const PointStatistics& night = *summary.points[0].statistics;
    const PointStatistics& day = *summary.points[1].statistics;

    // The thermal model: at night the ball is near the snow's temperature, by day solar-loaded.
    EXPECT_LT(std::abs(value(night, "ball", "temperature_k").mean -
                       value(night, "snow", "temperature_k").mean),
              5.0);
    EXPECT_GT(value(day, "ball", "temperature_k").mean - value(day, "snow", "temperature_k").mean,
              20.0);

    // Emission-dominated radial pattern at both times.
    const Estimate& c_night = value(night, "s1_pattern", "S1");
    const Estimate& c_day = value(day, "s1_pattern", "S1");
    EXPECT_GT(c_night.mean, 5.0 * c_night.error);
    EXPECT_GT(c_day.mean, 5.0 * c_day.error);
    EXPECT_LT(value(night, "ball_top", "S1").mean, 0.0);
    EXPECT_LT(value(day, "ball_bottom", "S1").mean, 0.0);

    // Night: the lower half's polarization is cancelled by the snow's reflected radiance; day: it
    // is not.
    const double night_ratio =
        value(night, "ball_bottom", "S1").mean / value(night, "ball_top", "S1").mean;
    const double day_ratio =
        value(day, "ball_bottom", "S1").mean / value(day, "ball_top", "S1").mean;
    EXPECT_LT(night_ratio, 0.5) << "bottom/top S1 at night";
    EXPECT_GT(day_ratio, 0.7) << "bottom/top S1 by day";

    // The pattern contrast at least doubles by day, far beyond the Monte-Carlo error.
    EXPECT_GT(c_day.mean, 2.0 * c_night.mean);
    EXPECT_GT(c_day.mean - c_night.mean, 10.0 * std::hypot(c_day.error, c_night.error));

    // What a person looks at: table, plots against time, contact sheets, and the animation, which
    // headless chromium plays: after one 600 ms tick of virtual time the page shows the second
    // frame.
    const auto out = dir / "out";
    for (const char* file :
         {"results.csv", "results.json", "plots/time_S1.png", "contact_sheet_S0.png",
          "contact_sheet_S1.png", "animation/frame_000.png", "animation/frame_001.png"})
        EXPECT_TRUE(std::filesystem::is_regular_file(out / file)) << file;
    const auto page = tirpol::test::run_command(
        "chromium --headless --no-sandbox --disable-gpu --virtual-time-budget=900 --dump-dom "
        "file://" +
            (out / "animation/index.html").string(),
        false);
    ASSERT_EQ(page.exit_code, 0) << "headless chromium (Debian package chromium) is needed: "
                                 << page.out;
    EXPECT_NE(page.out.find("src=\"frame_001.png\""), std::string::npos) << page.out;
    EXPECT_NE(page.out.find("<span id=\"label\">2026-01-16T12:00</span>"), std::string::npos)
        << page.out;
}

}  // namespace
}  // namespace tirpol::sweep
