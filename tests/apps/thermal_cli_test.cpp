// `tirpol sun` and `tirpol therm` as a user runs them.

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "test_support.h"

namespace {

using tirpol::test::CliRun;
using tirpol::test::run_cli;

TEST(ThermalCli, SunReproducesSpaReportExample) {
    // Reda & Andreas, NREL/TP-560-34302, Table A5.2: zenith 50.11162°, azimuth 194.34024°,
    // incidence 25.18700°.
    const CliRun r = run_cli(
        "sun --lat 39.742476 --lon -105.1786 --time 2003-10-17T12:30:30-07:00 --elevation-m "
        "1830.14 "
        "--pressure-mbar 820 --temperature-c 11 --delta-t-s 67 --tilt-deg 30 --surface-azimuth-deg "
        "170 --json");
    ASSERT_EQ(r.exit_code, 0) << r.out;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_NEAR(j["zenith_deg"].get<double>(), 50.11162, 1e-5);
    EXPECT_NEAR(j["azimuth_deg"].get<double>(), 194.34024, 1e-5);
    EXPECT_NEAR(j["surface"]["incidence_deg"].get<double>(), 25.18700, 1e-5);
    EXPECT_EQ(run_cli("sun --lat 39 --lon -105 --time noon").exit_code,
              2);  // a malformed option value: usage
    EXPECT_EQ(run_cli("sun --lat 99 --lon -105 --time 2003-10-17T12:00Z").exit_code, 2);
}

TEST(ThermalCli, ATimeWithoutAnOffsetIsAUsageErrorUnlessTheCommandStatesItsConvention) {
    // docs/cli.md "Times": `sun` has no site, so no standard time to assume; `therm --at` takes the
    // site's.
    const std::string sun = "sun --lat 39.742476 --lon -105.1786 --json --time ";
    const CliRun bare = run_cli(sun + "2003-10-17T12:30:30");
    EXPECT_EQ(bare.exit_code, 2) << bare.out;
    EXPECT_NE(bare.out.find("has no UTC offset"), std::string::npos) << bare.out;
    // The same instant three ways: offset in the text, --utc-offset-h, and UTC with Z (19:30:30Z).
    const CliRun with_offset = run_cli(sun + "2003-10-17T12:30:30-07:00", false);
    const CliRun with_option = run_cli(sun + "2003-10-17T12:30:30 --utc-offset-h -7", false);
    const CliRun in_utc = run_cli(sun + "2003-10-17T19:30:30Z", false);
    ASSERT_EQ(with_offset.exit_code, 0) << with_offset.out;
    ASSERT_EQ(with_option.exit_code, 0) << with_option.out;
    ASSERT_EQ(in_utc.exit_code, 0) << in_utc.out;
    const auto zenith = [](const CliRun& r) {
        return nlohmann::json::parse(r.out)["zenith_deg"].get<double>();
    };
    EXPECT_EQ(zenith(with_option), zenith(with_offset));
    EXPECT_EQ(zenith(in_utc), zenith(with_offset));
    // The help of each option that takes a time says what a time without an offset means.
    const CliRun sun_help = run_cli("sun --help", false),
                 therm_help = run_cli("therm --help", false);
    EXPECT_NE(sun_help.out.find("without one, --utc-offset-h is required"), std::string::npos)
        << sun_help.out;
    EXPECT_NE(therm_help.out.find("no offset: the site's standard time"), std::string::npos)
        << therm_help.out;
    const auto yaml = tirpol::test::source_dir() / "config/thermal/ball_on_snow_thermal.yaml";
    EXPECT_EQ(run_cli("therm " + yaml.string() + " --at 2026-01-16T25:00").exit_code, 2);
}

TEST(ThermalCli, ThermWritesTemperaturesCsvAndPlot) {
    tirpol::test::TempDir dir;
    const auto yaml = tirpol::test::source_dir() / "config/thermal/ball_on_snow_thermal.yaml";
    const CliRun r = run_cli("therm " + yaml.string() + " --at 2026-01-16T12:00 --json --csv " +
                             (dir / "t.csv").string() + " --plot " + (dir / "t.png").string());
    ASSERT_EQ(r.exit_code, 0) << r.out;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["time"], "2026-01-16T12:00:00-05:00");
    ASSERT_EQ(j["objects"].size(), 6u);
    std::map<std::string, double> t;
    for (const auto& o : j["objects"])
        t[o["name"].get<std::string>()] = o["temperature_k"].get<double>();
    EXPECT_GT(t["ball_top"], t["snow_field"]);    // paper Fig. 2: ball warmer than snow in the day
    EXPECT_GT(t["ball_south"], t["ball_north"]);  // sunlit side warmer
    EXPECT_GT(t["snow_field"], t["snow_in_ball_shadow"]);  // shadow is colder
    std::ifstream csv(dir / "t.csv");
    std::string header;
    std::getline(csv, header);
    EXPECT_EQ(header.rfind("object,material,tilt_deg,azimuth_deg", 0), 0u);
    std::ifstream png(dir / "t.png", std::ios::binary);
    char sig[8] = {};
    png.read(sig, 8);
    EXPECT_EQ(std::string(sig + 1, 3), "PNG");
    EXPECT_EQ(run_cli("therm " + yaml.string() + " --at 2030-01-01T00:00").exit_code, 1);
}

TEST(ThermalCli, ThermOnSceneReportsPredictedTemperatures) {
    const auto yaml = tirpol::test::source_dir() / "config/thermal/ball_on_snow_day_predicted.yaml";
    const CliRun r = run_cli("therm " + yaml.string() + " --json");
    ASSERT_EQ(r.exit_code, 0) << r.out;
    const auto j = nlohmann::json::parse(r.out);
    ASSERT_EQ(j["objects"].size(), 3u);
    EXPECT_GT(j["objects"][1]["max_temperature_k"].get<double>(),
              j["objects"][0]["max_temperature_k"].get<double>() + 10.0);
    EXPECT_EQ(run_cli("therm " + yaml.string() + " --plot x.png").exit_code, 1);
}

}  // namespace
