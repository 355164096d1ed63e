// Polarimetric calibration without known-source records: the analyzer from the
// polarizer's datasheet extinction ratio and the mount's axis offsets, and a method string that
// says which model was used.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "test_support.h"
#include "tirpol/calibration/analyzer.h"
#include "tirpol/calibration/session_calibration.h"
#include "tirpol/calibration/synthetic_session.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"

namespace tirpol::calibration {
namespace {

const std::vector<double> kAngles{0.0, 45.0, 90.0, 135.0};

TEST(DatasheetAnalyzer, ExtinctionRatioAndOffsetsGiveTheDiattenuatorRows) {
    // ER 150 → d = 149/151 (Chipman, Lam & Young eq 6.35 with t_max/t_min = 150).
    const auto m = datasheet_analyzer_model(kAngles, {150.0, {1.0, -0.5, 2.0, 0.0}});
    ASSERT_EQ(m.positions.size(), 4u);
    EXPECT_DOUBLE_EQ(m.positions[0].diattenuation, 149.0 / 151.0);
    EXPECT_NEAR(m.positions[0].extinction_ratio(), 150.0, 1e-9);
    EXPECT_DOUBLE_EQ(m.positions[1].axis_angle_deg, 44.5);
    EXPECT_DOUBLE_EQ(m.positions[2].axis_angle_deg, 92.0);
    const auto one = datasheet_analyzer_model(kAngles, {150.0, {1.5}});
    for (const auto& p : one.positions)
        EXPECT_DOUBLE_EQ(p.axis_angle_deg - p.nominal_angle_deg, 1.5);
    EXPECT_EQ(describe({150.0, {1.5}}), "datasheet (extinction ratio 150, axis offsets +1.50°)");
    EXPECT_THAT(
        [] {
            datasheet_analyzer_model(kAngles, {1.0, {}});
        },
        testing::ThrowsMessage<Error>(testing::HasSubstr("expected a finite t_max/t_min above 1")));
    EXPECT_THAT(
        [] {
            datasheet_analyzer_model(kAngles, {150.0, {1.0, 2.0}});
        },
        testing::ThrowsMessage<Error>(testing::HasSubstr("2 axis offsets for 4 analyzer angles")));
}

TEST(DatasheetAnalyzer, SessionWithoutKnownSourceUsesTheDatasheetAndSaysSo) {
    test::TempDir root;
    const Band band(8.0, 14.0);
    const SyntheticCamera cam;
    write_synthetic_sessions(root.path(), cam, synthetic_panel_scene(cam.width, cam.height, band),
                             band);
    // The same polarimetric session without its known-source description.
    auto json = nlohmann::json::parse(read_file(root / "polcal" / "session.json"));
    json["metadata"].erase("known_source");
    write_file_atomic(root / "polcal" / "session.json", json.dump(2));
    const auto radiometric = calibrate_radiometric_session(root / "lab", band);

    const auto ideal = calibrate_polarimetric_session(root / "polcal", radiometric);
    EXPECT_EQ(ideal.analyzer_method, "ideal (no known-source records)");
    EXPECT_DOUBLE_EQ(ideal.analyzer.positions[1].diattenuation, 1.0);

    const auto sheet = calibrate_polarimetric_session(
        root / "polcal", radiometric,
        DatasheetAnalyzer{cam.extinction_ratio, {cam.angle_offset_deg}});
    EXPECT_EQ(sheet.analyzer_method,
              "datasheet (extinction ratio 100, axis offsets +1.50°) (no known-source records)");
    for (const auto& p : sheet.analyzer.positions) {
        EXPECT_NEAR(p.extinction_ratio(), cam.extinction_ratio, 1e-9);
        EXPECT_DOUBLE_EQ(p.axis_angle_deg - p.nominal_angle_deg, cam.angle_offset_deg);
    }
}

}  // namespace
}  // namespace tirpol::calibration
