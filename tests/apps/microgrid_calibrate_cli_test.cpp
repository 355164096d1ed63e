// `tirpol calibrate microgrid` through the real executable: flat-field session of the synthetic
// microgrid bolometer → per-pixel calibration EXR → `tirpol reduce --pixel-calibration` of a
// uniform polarized field in band radiance; a session that cannot calibrate exits 1 naming it.

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cli_runner.h"
#include "test_support.h"
#include "tirpol/calibration/synthetic_session.h"
#include "tirpol/core/exr_io.h"

namespace {

using namespace tirpol;
using ::testing::HasSubstr;
using tirpol::test::run_cli;

TEST(MicrogridCalibrateCli, CalibratesFromFlatFieldsAndReducesInRadiance) {
    test::TempDir dir;
    calibration::SyntheticMicrogridCamera camera;
    camera.width = 32;
    camera.height = 24;
    camera.analyzer_spread = 0.2;
    camera.dead_x = 3;
    camera.dead_y = 3;
    camera.hot_x = 9;
    camera.hot_y = 10;
    camera.noisy_x = 20;
    camera.noisy_y = 12;
    const Band band(8.0, 14.0);
    calibration::write_synthetic_microgrid_flat_field(dir / "flat", camera, band);
    const double s0 = band.radiance(300.0), dolp = 0.3;
    calibration::write_synthetic_microgrid_scene(
        dir / "scene", camera,
        calibration::uniform_stokes_scene(camera, {s0, s0 * dolp * std::cos(std::numbers::pi / 3),
                                                   s0 * dolp * std::sin(std::numbers::pi / 3)}));
    const std::string pixcal = (dir / "pixcal.exr").string();
    const auto cal =
        run_cli(fmt::format("calibrate microgrid {} -o {}", (dir / "flat").string(), pixcal));
    ASSERT_EQ(cal.exit_code, 0) << cal.out;
    EXPECT_THAT(cal.out,
                HasSubstr("microgrid calibration 32×24 from 2 open-blackbody and 16 polarizer"));
    EXPECT_THAT(cal.out, HasSubstr("bad pixels: 3 (dead 1, hot 1, noisy 1"));
    const Image file = read_exr(pixcal);
    EXPECT_TRUE(file.has_channel("bad"));

    const auto reduce =
        run_cli(fmt::format("reduce {} --pixel-calibration {} -o {}", (dir / "scene").string(),
                            pixcal, (dir / "stokes.exr").string()));
    ASSERT_EQ(reduce.exit_code, 0) << reduce.out;
    const Image stokes = read_exr(dir / "stokes.exr");
    EXPECT_EQ(std::get<std::string>(stokes.attributes().at("units")), "W/(m^2 sr)");
    double sq = 0.0;
    for (float v : stokes.channel("DoLP")) sq += (v - dolp) * (v - dolp);
    EXPECT_LT(std::sqrt(sq / static_cast<double>(stokes.pixel_count())), 0.002);
    EXPECT_NEAR(stokes.at("S0", 5, 5), s0, 0.002 * s0);

    // The scene session has no flat fields: refused naming what is missing, exit 1.
    const auto refused = run_cli(fmt::format("calibrate microgrid {} -o {}",
                                             (dir / "scene").string(), (dir / "x.exr").string()));
    EXPECT_EQ(refused.exit_code, 1) << refused.out;
    EXPECT_THAT(refused.out, HasSubstr("microgrid_flat_field"));
    // An inverted band is a usage error.
    const auto band_error = run_cli(fmt::format("calibrate microgrid {} --band-um 14 8 -o {}",
                                                (dir / "flat").string(), (dir / "y.exr").string()));
    EXPECT_EQ(band_error.exit_code, 2) << band_error.out;
}

}  // namespace
