// The text of `tirpol calibrate radiometric`: the median gain and residual of the maps, each
// set-point's residual with its FPA temperature when there is one, the bad pixels counted by class
// (a pixel's bits may name several classes) and the files written.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "tirpol/calibration/calibration_chain.h"
#include "tirpol/calibration/radiometric.h"

namespace tirpol::calibration {
namespace {

using ::testing::HasSubstr;

TEST(CalibrationRun, RadiometricTextSummarisesMapsSetPointsAndBadPixels) {
    RadiometricRun run;
    run.options.output = "cal.exr";
    run.options.summary = "cal.summary";
    auto& cal = run.calibration;
    cal.camera_id = "sim:cam";
    cal.width = 2;
    cal.height = 2;
    cal.gain = {10.0f, 12.0f, 11.0f, 30.0f};
    cal.residual_rms = {0.5f, 0.5f, 0.5f, 0.5f};
    cal.bad = {0.0f, static_cast<float>(kDead | kHot), 0.0f, static_cast<float>(kNoisy)};
    cal.temperatures_k = {290.0, 320.0};
    cal.warnings = {"drift not modelled"};
    run.quality.set_points = {SetPointResidual{290.0, NAN, 0, 0, 1.24, 20.0, 0, 4},
                              SetPointResidual{320.0, 305.5, 0, 0, -2.0, 30.0, 0, 4}};
    run.quality.nedt_median_k = 0.045;
    run.quality.nedt_temperature_k = 300.0;
    const std::string text = radiometric_run_text(run);
    EXPECT_THAT(text, HasSubstr("radiometric calibration of sim:cam (2×2, 2 blackbody frames, "
                                "linear model)\n"));
    EXPECT_THAT(text, HasSubstr("    290.00 K: mean    +1.2 mK, RMS   20.0 mK\n"));
    EXPECT_THAT(text, HasSubstr("    320.00 K at FPA 305.50 K: mean    -2.0 mK"));
    EXPECT_THAT(text, HasSubstr("  median NEDT 45.0 mK at 300.0 K\n"));
    EXPECT_THAT(text, HasSubstr("  warning: drift not modelled\n"));
    EXPECT_THAT(text, HasSubstr("  bad pixels: 2 (dead 1, hot 1, noisy 1, non-linear 0, "
                                "saturated 0)\n"));
    EXPECT_THAT(text, HasSubstr("  written: cal.exr and cal.summary/ (index.html"));
    EXPECT_THAT(text, ::testing::Not(HasSubstr("FPA-temperature model")));
}

}  // namespace
}  // namespace tirpol::calibration
