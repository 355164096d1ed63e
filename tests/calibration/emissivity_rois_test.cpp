// The emissivity ROI file is held to whole-pixel rectangles and non-negative uncertainties, and an
// extracted ε_S0 outside [0, 1] beyond noise carries a warning (before: non-integer rectangles
// were truncated silently, temperature_std_k: -1 was accepted, ε_S0 = 1.48 was reported without a
// word).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test_support.h"
#include "tirpol/calibration/emissivity_extraction.h"
#include "tirpol/core/error.h"

namespace tirpol::calibration {
namespace {

std::string error_of(const std::string& yaml) {
    test::TempDir dir;
    test::write_text(dir / "rois.yaml", yaml);
    try {
        EmissivityRois::load((dir / "rois.yaml").string());
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

const std::string kReflector = "reflector: {rect: [0, 0, 4, 4]}\n";

TEST(EmissivityRois, FractionalRectanglesAreErrorsNotTruncated) {
    EXPECT_THAT(
        error_of(kReflector + "targets:\n  - {name: p, rect: [10.5, 2, 4, 4], view_angle_deg: 30, "
                              "temperature_k: 300}\n"),
        testing::AllOf(testing::HasSubstr("targets[0].rect"), testing::HasSubstr("whole pixels"),
                       testing::HasSubstr("10.5")));
    EXPECT_THAT(error_of("reflector: {rect: [0, 0, 1e300, 4]}\ntargets: []\n"),
                testing::HasSubstr("whole pixels"));
    EXPECT_THAT(error_of("reflector: {rect: [-1, 0, 4, 4]}\ntargets: []\n"),
                testing::HasSubstr("whole pixels"));
}

TEST(EmissivityRois, NegativeTemperatureUncertaintyIsAnError) {
    EXPECT_THAT(
        error_of(kReflector + "targets:\n  - {name: p, rect: [10, 2, 4, 4], view_angle_deg: 30, "
                              "temperature_k: 300, temperature_std_k: -1}\n"),
        testing::AllOf(testing::HasSubstr("temperature_std_k"),
                       testing::HasSubstr("out of range")));
}

TEST(EmissivityRois, EmissivityAboveOneBeyondNoiseIsFlagged) {
    // A uniform target brighter than a blackbody at its stated temperature: ε_S0 > 1.
    const Band band(8.0, 14.0);
    Image im(20, 10);
    auto& s0 = im.add_channel("S0");
    im.add_channel("S1");
    im.add_channel("S2");
    const double l_dw = band.radiance(240.0), l_bb = band.radiance(290.0);
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 20; ++x)
            s0[im.index(x, y)] = static_cast<float>(x < 10 ? l_dw : l_dw + 1.48 * (l_bb - l_dw));
    EmissivityRois rois;
    rois.reflector.rect = {0, 0, 10, 10};
    rois.targets = {{"hot_panel", {10, 0, 10, 10}, 30.0, 290.0, 0.5, std::nullopt}};
    const auto results = extract_emissivity(im, rois, band);
    ASSERT_EQ(results.size(), 1u);
    EXPECT_NEAR(results[0].eps_s0, 1.48, 1e-4);
    ASSERT_EQ(results[0].warnings.size(), 1u);
    EXPECT_THAT(results[0].warnings[0],
                testing::AllOf(testing::HasSubstr("hot_panel"), testing::HasSubstr("1.480"),
                               testing::HasSubstr("outside [0, 1]")));
    rois.targets[0].temperature_k = 290.0;
    const Image plausible = [&] {
        Image p = im;
        for (int y = 0; y < 10; ++y)
            for (int x = 10; x < 20; ++x)
                p.channel("S0")[p.index(x, y)] = static_cast<float>(l_dw + 0.9 * (l_bb - l_dw));
        return p;
    }();
    EXPECT_TRUE(extract_emissivity(plausible, rois, band)[0].warnings.empty());
}

// The reflector's own emission (docs/calibration.md): emissivity needs the reflector's temperature.
TEST(EmissivityRois, ReflectorEmissionKeysAndErrors) {
    const std::string targets =
        "targets:\n  - {name: p, rect: [10, 2, 4, 4], view_angle_deg: 30, temperature_k: 300}\n";
    test::TempDir dir;
    test::write_text(dir / "rois.yaml",
                     "reflector: {rect: [0, 0, 4, 4], emissivity: 0.06, emissivity_std: 0.01, "
                     "temperature_k: 281.5, "
                     "temperature_std_k: 0.3}\n" +
                         targets);
    const EmissivityRois loaded = EmissivityRois::load((dir / "rois.yaml").string());
    EXPECT_DOUBLE_EQ(loaded.reflector.emissivity, 0.06);
    EXPECT_DOUBLE_EQ(loaded.reflector.emissivity_std, 0.01);
    EXPECT_DOUBLE_EQ(*loaded.reflector.temperature_k, 281.5);
    EXPECT_DOUBLE_EQ(loaded.reflector.temperature_std_k, 0.3);

    EXPECT_THAT(
        error_of("reflector: {rect: [0, 0, 4, 4], emissivity: 0.06}\n" + targets),
        testing::AllOf(testing::HasSubstr("reflector"), testing::HasSubstr("temperature_k")));
    EXPECT_THAT(
        error_of("reflector: {rect: [0, 0, 4, 4], emissivity: 1.0, temperature_k: 280}\n" +
                 targets),
        testing::AllOf(testing::HasSubstr("emissivity"), testing::HasSubstr("out of range")));
}

}  // namespace
}  // namespace tirpol::calibration
