// `tirpol emissivity`'s library side: the report of a library material at a wavelength and over a
// band, its CSV file, JSON keys and text table.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "test_support.h"
#include "tirpol/core/error.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/output_guard.h"
#include "tirpol/materials/emissivity.h"

namespace tirpol::materials {
namespace {

using ::testing::HasSubstr;

EmissivityReportOptions water() {
    EmissivityReportOptions o;
    o.material = (test::source_dir() / "config/materials/water.yaml").string();
    o.angles_deg = {0.0, 45.0, 80.0};
    return o;
}

// Emission at normal incidence is unpolarized; at 80° it is polarized in the plane of emission
// (ε_S1 < 0), and ε_S0 + DHR = 1 (Kirchhoff) on every row.
TEST(EmissivityReport, WaterAtOneWavelengthObeysKirchhoffAndPolarizesObliquely) {
    EmissivityReportOptions o = water();
    o.wavelength_um = 10.0;
    const EmissivityReport r = emissivity_report(o);
    ASSERT_EQ(r.rows.size(), 3u);
    EXPECT_NEAR(r.rows[0].dolp, 0.0, 1e-9);
    EXPECT_LT(r.rows[2].e(1), 0.0);
    for (const auto& row : r.rows) EXPECT_NEAR(row.e(0) + row.dhr, 1.0, 1e-9);
    EXPECT_EQ(r.spectral, "10 µm");
    const nlohmann::json j = emissivity_report_json(r);
    EXPECT_EQ(j["wavelength_um"].get<double>(), 10.0);
    EXPECT_FALSE(j.contains("band_um"));
    EXPECT_EQ(j["file"], o.material);
    ASSERT_EQ(j["rows"].size(), 3u);
    EXPECT_EQ(j["rows"][2]["e_s1"].get<double>(), r.rows[2].e(1));
}

TEST(EmissivityReport, BandReportWritesItsCsvAndNamesItInTheText) {
    EmissivityReportOptions o = water();
    o.band_um = {8.0, 12.0};
    o.temperature_k = 290.0;
    const test::TempDir dir("emissivity_report");
    o.csv = (dir / "water.csv").string();
    const EmissivityReport r = emissivity_report(o);
    EXPECT_EQ(r.spectral, "8–12 µm band at 290 K");
    std::ifstream in(o.csv);
    std::stringstream csv;
    csv << in.rdbuf();
    EXPECT_EQ(csv.str(), emissivity_csv(r.rows));
    const nlohmann::json j = emissivity_report_json(r);
    EXPECT_EQ(j["band_um"], nlohmann::json({8.0, 12.0}));
    EXPECT_TRUE(j["rsr"].is_null());
    EXPECT_EQ(j["temperature_k"].get<double>(), 290.0);
    const std::string text = emissivity_report_text(r);
    EXPECT_THAT(text, HasSubstr("8–12 µm band at 290 K"));
    EXPECT_THAT(text, HasSubstr("table: " + o.csv + "\n"));
    // Normal incidence: S1 is rounding noise and prints as 0, never as -0.00000.
    EXPECT_THAT(text, HasSubstr("     0.00"));
    EXPECT_THAT(text, ::testing::Not(HasSubstr("-0.00000")));
}

TEST(EmissivityReport, BandBelowZeroKelvinIsAnError) {
    EmissivityReportOptions o = water();
    o.band_um = {8.0, 12.0};
    o.temperature_k = 0.0;
    EXPECT_THROW(emissivity_report(o), Error);
}

TEST(EmissivityReport, ABandTemperatureNotAboveZeroIsAnErrorOfItsOption) {
    EmissivityReportOptions o = water();
    o.band_um = {8.0, 12.0};
    o.temperature_k = -1.0;
    try {
        emissivity_report(o);
        FAIL() << "a band temperature of -1 K was accepted";
    } catch (const OptionValueError& e) {
        EXPECT_EQ(e.option(), "--temperature-k");
    }
}

TEST(EmissivityReport, OutputsAreCheckedAgainstTheMaterialBeforeItLoads) {
    const test::TempDir dir("emissivity_report_guard");
    EmissivityReportOptions o = water();
    o.material = (dir / "material.yaml").string();
    test::write_text(o.material, "not a material");
    o.csv = o.material;
    o.force = true;
    EXPECT_THROW(emissivity_report(o), OutputConflict);
    o.csv.clear();
    o.plot = (dir / "plot.png").string();
    test::write_text(o.plot, "kept");
    o.force = false;
    EXPECT_THROW(emissivity_report(o), OutputConflict);
    std::ifstream in(o.plot);
    std::string kept;
    in >> kept;
    EXPECT_EQ(kept, "kept");
}

}  // namespace
}  // namespace tirpol::materials
