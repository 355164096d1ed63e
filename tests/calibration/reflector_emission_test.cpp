// The IR reflector emits too: by Kirchhoff its S0 in uniform surroundings is (1 − ε_r)·L_dw +
// ε_r·L_BB(T_r). A reflector at ambient seen at night (a gold-coated diffuser: ε_r ≈ 0.03–0.12 over
// view angles) adds a sizeable part of L_BB − L_dw, which eq 17 would read as downwelling.
// downwelled_radiance removes it; its standard error follows to first order.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "stokes_image.h"
#include "tirpol/calibration/emissivity_extraction.h"
#include "tirpol/core/error.h"

namespace tirpol::calibration {
namespace {

constexpr int kW = 40, kH = 20;
constexpr double kReflectorEmissivity = 0.1, kReflectorK = 285.0, kSkyK = 240.0, kPanelK = 295.0;

/// Left half: the reflector; right half: a panel with ε_S0 = 0.92, ε_S1 = −0.03. No noise.
Image scene(const Band& band) {
    const double l_dw = band.radiance(kSkyK), l_bb = band.radiance(kPanelK);
    const double l_reflector =
        (1.0 - kReflectorEmissivity) * l_dw + kReflectorEmissivity * band.radiance(kReflectorK);
    return test::stokes_image(kW, kH, [&](int x, int) -> std::array<double, 3> {
        if (x < kW / 2) return {l_reflector, 0.0, 0.0};
        return {0.08 * l_dw + 0.92 * l_bb, -0.03 * (l_bb - l_dw), 0.0};
    });
}

EmissivityRois rois() {
    EmissivityRois r;
    r.reflector = {{1, 1, 18, 18}, kReflectorEmissivity, 0.0, kReflectorK, 0.0};
    r.targets.push_back({"panel", {21, 1, 18, 18}, 40.0, kPanelK, 0.0, std::nullopt});
    return r;
}

TEST(ReflectorEmission, IsRemovedFromTheDownwelling) {
    const Band band(8.0, 14.0);
    const Image im = scene(band);
    EXPECT_NEAR(downwelled_radiance(im, rois().reflector, band).mean, band.radiance(kSkyK), 1e-4);
    const auto corrected = extract_emissivity(im, rois(), band).front();
    EXPECT_NEAR(corrected.eps_s0, 0.92, 1e-5);
    EXPECT_NEAR(corrected.eps_s1, -0.03, 1e-5);

    // Taken as a perfect reflector (the paper's eq 17 as written), L_dw is 10 % of (L_BB(T_r) −
    // L_dw) too high here and ε_S0 comes out 0.007 too low.
    EmissivityRois perfect = rois();
    perfect.reflector.emissivity = 0.0;
    const auto naive = extract_emissivity(im, perfect, band).front();
    EXPECT_LT(naive.eps_s0, 0.915);
    EXPECT_LT(naive.eps_s1, -0.031);
}

TEST(ReflectorEmission, UncertaintiesPropagate) {
    const Band band(8.0, 14.0);
    const Image im = scene(band);  // noiseless: the ROI scatter adds nothing
    EmissivityReflector r = rois().reflector;
    r.temperature_std_k = 1.0;
    const double e = kReflectorEmissivity;
    EXPECT_NEAR(downwelled_radiance(im, r, band).standard_error,
                e * band.radiance_dT(kReflectorK) / (1.0 - e), 1e-6);
    r.temperature_std_k = 0.0;
    r.emissivity_std = 0.01;  // ∂L_dw/∂ε_r = (S0_r − L_BB(T_r))/(1 − ε_r)²
    const double s0 = (1.0 - e) * band.radiance(kSkyK) + e * band.radiance(kReflectorK);
    EXPECT_NEAR(downwelled_radiance(im, r, band).standard_error,
                std::abs(s0 - band.radiance(kReflectorK)) / ((1.0 - e) * (1.0 - e)) * 0.01, 1e-5);
}

TEST(ReflectorEmission, AnEmissivityWithoutATemperatureIsAnError) {
    const Band band(8.0, 14.0);
    EmissivityReflector bad = rois().reflector;
    bad.temperature_k.reset();
    EXPECT_THAT(
        [&] { downwelled_radiance(scene(band), bad, band); },
        testing::ThrowsMessage<Error>(testing::HasSubstr("needs the reflector's temperature")));
}

}  // namespace
}  // namespace tirpol::calibration
