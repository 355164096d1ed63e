// Registration: a known homography from control points, a known shift and scale by ECC (residual
// < 0.5 px), identity when images match, and clear errors when registration is impossible.

#include "tirpol/report/registration.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "error_of.h"
#include "synthetic_pair.h"
#include "test_support.h"
#include "tirpol/core/error.h"

using tirpol::test::error_of;

using namespace tirpol::report;
using ::testing::HasSubstr;

namespace {

PixelPoint apply(const std::array<double, 9>& h, PixelPoint p) {
    const double w = h[6] * p.x + h[7] * p.y + h[8];
    return {(h[0] * p.x + h[1] * p.y + h[2]) / w, (h[3] * p.x + h[4] * p.y + h[5]) / w};
}

// The simulated pixel a measured pixel should map to when measured(x) = scene(x − shift).
void expect_maps_like_shift(const Registration& reg, double dx, double dy, int w, int h,
                            double tol) {
    for (const PixelPoint p :
         {PixelPoint{5, 5}, PixelPoint{w - 5.0, 5}, PixelPoint{w / 2.0, h / 2.0},
          PixelPoint{5, h - 5.0}, PixelPoint{w - 5.0, h - 5.0}}) {
        const PixelPoint q = apply(reg.measured_to_simulated, p);
        EXPECT_NEAR(q.x, p.x - dx, tol) << "at (" << p.x << ", " << p.y << ")";
        EXPECT_NEAR(q.y, p.y - dy, tol) << "at (" << p.x << ", " << p.y << ")";
    }
}

test::SyntheticPairOptions quiet(double dx, double dy) {
    test::SyntheticPairOptions o;
    o.shift_x_px = dx;
    o.shift_y_px = dy;
    o.measured_sigma = 0.02;
    o.simulated_sigma = 0.01;
    return o;
}

}  // namespace

TEST(ReportRegistration, ControlPointsRecoverAKnownHomography) {
    // A mild perspective: simulated = H_true(measured).
    const std::array<double, 9> truth{1.02, 0.03, -4.0, -0.02, 0.98, 2.5, 1e-5, -2e-5, 1.0};
    std::vector<TiePoint> cps;
    for (const PixelPoint m : {PixelPoint{10, 12}, PixelPoint{150, 8}, PixelPoint{160, 120},
                               PixelPoint{14, 130}, PixelPoint{80, 60}, PixelPoint{40, 100}})
        cps.push_back({m, apply(truth, m)});
    const auto pair = test::make_synthetic_pair(quiet(0, 0));
    const Registration reg =
        register_images(pair.measured, pair.simulated, RegistrationMethod::ControlPoints, cps);
    EXPECT_EQ(reg.model, "homography");
    ASSERT_TRUE(reg.control_point_rms_px.has_value());
    EXPECT_LT(*reg.control_point_rms_px, 1e-4);  // exact data: only round-off remains
    for (std::size_t i = 0; i < 9; ++i)
        EXPECT_NEAR(reg.measured_to_simulated[i], truth[i],
                    1e-5 * std::max(1.0, std::abs(truth[i])))
            << "H[" << i << "]";
}

TEST(ReportRegistration, ControlPointsRecoverAShiftOfTheImagesAndReportResidual) {
    const double dx = 3.0, dy = -2.0;
    const auto pair = test::make_synthetic_pair(quiet(dx, dy));
    std::vector<TiePoint> cps;
    for (const PixelPoint s :
         {PixelPoint{20, 20}, PixelPoint{170, 20}, PixelPoint{170, 120}, PixelPoint{20, 120}})
        cps.push_back({{s.x + dx, s.y + dy}, s});
    const Registration reg =
        register_images(pair.measured, pair.simulated, RegistrationMethod::ControlPoints, cps);
    expect_maps_like_shift(reg, dx, dy, 192, 144, 1e-6);
    EXPECT_LT(std::hypot(reg.residual_shift_px[0], reg.residual_shift_px[1]), 0.5);
}

TEST(ReportRegistration, EccRecoversASubpixelShift) {
    const double dx = 2.6, dy = -1.7;
    const auto pair = test::make_synthetic_pair(quiet(dx, dy));
    const Registration reg =
        register_images(pair.measured, pair.simulated, RegistrationMethod::Auto, {});
    EXPECT_NE(reg.model, "identity");
    expect_maps_like_shift(reg, dx, dy, 192, 144, 0.5);
    EXPECT_LT(std::hypot(reg.residual_shift_px[0], reg.residual_shift_px[1]), 0.5);
    ASSERT_TRUE(reg.ecc_correlation.has_value());
    EXPECT_GT(*reg.ecc_correlation, 0.9);
}

TEST(ReportRegistration, EccRegistersASimulationRenderedAtTwiceTheResolution) {
    // The simulation is the same scene rendered at 2× the pixel count (same aspect ratio).
    auto so = quiet(0, 0);
    so.width = 384;
    so.height = 288;
    const auto sim = test::make_synthetic_pair(so).simulated;
    auto mo = quiet(0, 0);
    const auto meas = test::make_synthetic_pair(mo).measured;
    const Registration reg = register_images(meas, sim, RegistrationMethod::Auto, {});
    // Pixel centre x_m ↔ 2 x_m + 0.5 in the 2× grid.
    for (const PixelPoint p : {PixelPoint{10, 10}, PixelPoint{180, 130}, PixelPoint{96, 72}}) {
        const PixelPoint q = apply(reg.measured_to_simulated, p);
        EXPECT_NEAR(q.x, 2 * p.x + 0.5, 1.0);
        EXPECT_NEAR(q.y, 2 * p.y + 0.5, 1.0);
    }
    EXPECT_LT(std::hypot(reg.residual_shift_px[0], reg.residual_shift_px[1]), 0.5);
}

TEST(ReportRegistration, MatchingImagesGiveIdentity) {
    const auto pair = test::make_synthetic_pair(quiet(0, 0));
    const Registration reg =
        register_images(pair.measured, pair.simulated, RegistrationMethod::Auto, {});
    EXPECT_EQ(reg.model, "identity");
    EXPECT_THAT(reg.note, HasSubstr("already"));
    EXPECT_LT(std::hypot(reg.residual_shift_px[0], reg.residual_shift_px[1]), 0.2);
    // And resampling through identity returns the simulation unchanged.
    const auto same = resample_to_measured(pair.simulated, reg, 192, 144);
    EXPECT_EQ(same.channel("S1"), pair.simulated.channel("S1"));
}

TEST(ReportRegistration, AutoNeverWarpsAnAlignedNoisyPair) {
    // Aligned pairs with 5× the usual noise, several noise draws: ECC may settle a fraction of a
    // pixel away, but a warp that does not match the edges better must not replace the identity
    // (bilinear resampling would also smooth the simulation's noise and bias z).
    for (std::uint32_t seed : {1u, 2u, 3u}) {
        test::SyntheticPairOptions o;
        o.measured_sigma = 0.25;
        o.simulated_sigma = 0.15;
        o.seed = seed;
        const auto pair = test::make_synthetic_pair(o);
        const Registration reg =
            register_images(pair.measured, pair.simulated, RegistrationMethod::Auto, {});
        EXPECT_EQ(reg.model, "identity") << "seed " << seed << ": " << reg.note;
        EXPECT_THAT(reg.note, HasSubstr("already")) << reg.note;
        EXPECT_EQ(resample_to_measured(pair.simulated, reg, 192, 144).channel("S0"),
                  pair.simulated.channel("S0"));
    }
}

TEST(ReportRegistration, AutoKeepsAWarpThatMatchesTheEdgesBetter) {
    // A real 0.8 px shift: the warp lowers the S0 edge mismatch well beyond the 10 % threshold.
    const auto pair = test::make_synthetic_pair(quiet(0.8, 0.0));
    const Registration reg =
        register_images(pair.measured, pair.simulated, RegistrationMethod::Auto, {});
    EXPECT_NE(reg.model, "identity") << reg.note;
    ASSERT_TRUE(reg.identity_edge_mismatch && reg.registered_edge_mismatch);
    EXPECT_LT(*reg.registered_edge_mismatch,
              (1.0 - kRegistrationMinImprovement) * *reg.identity_edge_mismatch);
    expect_maps_like_shift(reg, 0.8, 0.0, 192, 144, 0.2);
}

TEST(ReportRegistration, NoneReportsTheMisalignmentItLeaves) {
    const auto pair = test::make_synthetic_pair(quiet(2.0, 0.0));
    const Registration reg =
        register_images(pair.measured, pair.simulated, RegistrationMethod::None, {});
    EXPECT_EQ(reg.model, "identity");
    EXPECT_NEAR(std::abs(reg.residual_shift_px[0]), 2.0, 0.3);
    EXPECT_NEAR(reg.residual_shift_px[1], 0.0, 0.3);
}

TEST(ReportRegistration, ResamplingMarksPixelsOutsideTheSimulationAsNaN) {
    const auto pair = test::make_synthetic_pair(quiet(0, 0));
    Registration reg;
    reg.model = "translation";
    reg.measured_to_simulated = {1, 0, 10, 0, 1, 0, 0, 0, 1};  // measured x ↔ simulated x + 10
    const auto out = resample_to_measured(pair.simulated, reg, 192, 144);
    EXPECT_TRUE(std::isnan(out.at("S0", 185, 50)));
    EXPECT_FLOAT_EQ(out.at("S0", 20, 50), pair.simulated.at("S0", 30, 50));
}

TEST(ReportRegistration, ResampledVarianceIsTheVarianceOfTheInterpolatedNoise) {
    // White noise of variance 1 shifted by half a pixel in x and y: each output is the mean of four
    // independent samples, variance 4 · (1/4)² = 1/4; the resampled S0_var must say the same.
    const int w = 200, h = 160;
    tirpol::Image sim(w, h);
    auto& s0 = sim.add_channel("S0");
    sim.add_channel("S0_var", 1.0f);
    std::mt19937 rng(11);
    std::normal_distribution<float> n;
    for (auto& v : s0) v = n(rng);
    Registration reg;
    reg.model = "translation";
    reg.measured_to_simulated = {1, 0, 0.5, 0, 1, 0.5, 0, 0, 1};
    const auto out = resample_to_measured(sim, reg, w, h);
    double sum2 = 0.0;
    std::size_t count = 0;
    for (float v : out.channel("S0"))
        if (std::isfinite(v)) {
            sum2 += v * v;
            ++count;
        }
    const double sample_variance = sum2 / static_cast<double>(count);
    EXPECT_NEAR(sample_variance, 0.25, 0.25 * 4.0 * std::sqrt(2.0 / static_cast<double>(count)));
    EXPECT_FLOAT_EQ(out.at("S0_var", 50, 50), 0.25f);
}

TEST(ReportRegistration, ImpossibleRegistrationsFailClearly) {
    const auto meas = test::make_synthetic_pair(quiet(0, 0)).measured;
    auto o = quiet(0, 0);
    o.width = 160;  // aspect 160/144 ≠ 192/144
    const auto sim = test::make_synthetic_pair(o).simulated;
    auto msg = error_of([&] { register_images(meas, sim, RegistrationMethod::Auto, {}); });
    EXPECT_THAT(msg, HasSubstr("192×144"));
    EXPECT_THAT(msg, HasSubstr("160×144"));
    EXPECT_THAT(msg, HasSubstr("control points"));
    msg = error_of([&] { register_images(meas, sim, RegistrationMethod::None, {}); });
    EXPECT_THAT(msg, HasSubstr("control points"));
    msg = error_of([&] {
        register_images(meas, sim, RegistrationMethod::ControlPoints,
                        {{{0, 0}, {0, 0}}, {{1, 0}, {1, 0}}});
    });
    EXPECT_THAT(msg, HasSubstr("at least 4 pairs"));
    EXPECT_THAT(error_of([] { parse_registration_method("ecc"); }),
                HasSubstr("none, auto, control-points"));
}

TEST(ReportRegistration, ControlPointFileErrorsNameTheLine) {
    tirpol::test::TempDir dir;
    tirpol::test::write_text(
        dir / "cp.yaml",
        "- measured: [1, 2]\n  simulated: [3, 4]\n- measured: [1, 2]\n  simulted: [3, 4]\n");
    const auto msg = error_of([&] { load_control_points(dir / "cp.yaml"); });
    EXPECT_THAT(msg, HasSubstr("cp.yaml:4"));
    EXPECT_THAT(msg, HasSubstr("simulted"));
    tirpol::test::write_text(dir / "ok.yaml", "- {measured: [1, 2], simulated: [3.5, 4]}\n");
    const auto cps = load_control_points(dir / "ok.yaml");
    ASSERT_EQ(cps.size(), 1u);
    EXPECT_DOUBLE_EQ(cps[0].simulated.x, 3.5);
}
