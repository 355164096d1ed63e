// `tirpol therm`'s library side: a standalone thermal file simulated to a time (the paper's Fig. 2
// ordering of the ball and the snow), a scene file's predicted ranges, the CSV tables, the formats
// and which errors name an option value (usage) and which the file.

#include "tirpol/simulation/therm_report.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "test_support.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/output_guard.h"

namespace tirpol::simulation {
namespace {

using ::testing::HasSubstr;

std::string thermal_file() {
    return (test::source_dir() / "config/thermal/ball_on_snow_thermal.yaml").string();
}

TEST(ThermReport, StandaloneFileAtNoonWarmsTheBallAboveTheSnowAndWritesItsCsv) {
    const test::TempDir dir("therm_report");
    ThermOptions o;
    o.file = thermal_file();
    o.at = "2026-01-16T12:00";
    o.csv = (dir / "t.csv").string();
    const ThermReport r = run_therm(o);
    ASSERT_TRUE(r.thermal_scene && r.run);
    const nlohmann::json j = therm_report_json(r);
    EXPECT_EQ(j["time"], "2026-01-16T12:00:00-05:00");
    std::map<std::string, double> t;
    for (const auto& obj : j["objects"])
        t[obj["name"].get<std::string>()] = obj["temperature_k"].get<double>();
    EXPECT_GT(t.at("ball_top"), t.at("snow_field"));
    EXPECT_GT(t.at("snow_field"), t.at("snow_in_ball_shadow"));
    std::ifstream in(o.csv);
    std::stringstream csv;
    csv << in.rdbuf();
    EXPECT_EQ(csv.str(), thermal::thermal_run_csv(*r.thermal_scene, *r.run));
    const std::string text = therm_report_text(r);
    EXPECT_THAT(text, HasSubstr(o.file + " at 2026-01-16T12:00:00-05:00 ("));
    EXPECT_THAT(text, HasSubstr("ball_top "));
}

TEST(ThermReport, AtThatDoesNotParseIsAnOptionValueErrorAndSceneOnlyOptionsAreFileErrors) {
    ThermOptions o;
    o.file = thermal_file();
    o.at = "2026-01-16T25:00";
    try {
        run_therm(o);
        FAIL() << "expected an error";
    } catch (const OptionValueError& e) {
        EXPECT_EQ(e.option(), "--at");
    }
    o.at = "2026-01-16T12:00";
    o.export_dir = "exports";
    EXPECT_THROW(run_therm(o), Error);
}

TEST(ThermReport, SceneFileReportsEachObjectsPredictedRange) {
    ThermOptions o;
    o.file = (test::source_dir() / "config/thermal/ball_on_snow_day_predicted.yaml").string();
    const ThermReport r = run_therm(o);
    EXPECT_FALSE(r.thermal_scene);
    ASSERT_EQ(r.scene_objects.size(), 3u);
    for (const auto& t : r.scene_objects) EXPECT_LE(t.min_temperature_k, t.max_temperature_k);
    const nlohmann::json j = therm_report_json(r);
    EXPECT_EQ(j["objects"][1]["max_temperature_k"].get<double>(),
              r.scene_objects[1].max_temperature_k);
    EXPECT_THAT(therm_report_text(r), HasSubstr(r.scene_objects[0].name));
    o.plot = "day.png";
    try {
        run_therm(o);
        FAIL() << "expected an error";
    } catch (const OptionValueError&) {
        FAIL() << "--plot with a scene file is an input error, not a usage error";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("--plot needs a standalone thermal file"));
    }
}

TEST(ThermReport, OutputsAreCheckedAgainstTheFileBeforeItLoads) {
    const test::TempDir dir("therm_report_guard");
    ThermOptions o;
    o.file = thermal_file();
    o.csv = o.file;
    o.force = true;
    EXPECT_THROW(run_therm(o), OutputConflict);
    o.csv.clear();
    o.plot = (dir / "day.png").string();
    test::write_text(o.plot, "kept");
    o.force = false;
    EXPECT_THROW(run_therm(o), OutputConflict);
    std::ifstream in(o.plot);
    std::string kept;
    in >> kept;
    EXPECT_EQ(kept, "kept");
}

}  // namespace
}  // namespace tirpol::simulation
