// `tirpol planck`'s library side: the temperature → radiance → brightness-temperature round trip
// through the answers, their JSON keys and text, and the errors.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tirpol/core/error.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/path_info.h"

namespace tirpol {
namespace {

using ::testing::HasSubstr;

TEST(PlanckReport, RadianceOfATemperatureGivesItBackAsBrightnessTemperature) {
    const Band band(8.0, 14.0);
    PlanckQuery forward;
    forward.band_um = {8.0, 14.0};
    forward.temperature_k = 300.0;
    const PlanckAnswer a = evaluate_planck(band, forward);
    EXPECT_EQ(a.radiance_w_m2_sr, band.radiance(300.0));
    EXPECT_GT(*a.radiance_dT_w_m2_sr_k, 0.0);
    PlanckQuery backward;
    backward.band_um = {8.0, 14.0};
    backward.radiance_w_m2_sr = a.radiance_w_m2_sr;
    const PlanckAnswer b = evaluate_planck(band, backward);
    EXPECT_NEAR(*b.brightness_temperature_k, 300.0, 1e-6);
    EXPECT_FALSE(b.radiance_dT_w_m2_sr_k);
}

TEST(PlanckReport, JsonKeysDependOnTheQuestion) {
    const Band band(8.0, 14.0);
    PlanckQuery q;
    q.band_um = {8.0, 14.0};
    q.temperature_k = 350.0;
    const nlohmann::json t = planck_answer_json(evaluate_planck(band, q));
    EXPECT_EQ(t["band_um"], nlohmann::json({8.0, 14.0}));
    EXPECT_TRUE(t["rsr"].is_null());
    EXPECT_EQ(t["temperature_k"].get<double>(), 350.0);
    EXPECT_TRUE(t.contains("radiance_dT_w_m2_sr_k"));
    EXPECT_FALSE(t.contains("brightness_temperature_k"));
    q.temperature_k.reset();
    q.radiance_w_m2_sr = 30.0;
    q.rsr = "camera.csv";
    const nlohmann::json l = planck_answer_json(evaluate_planck(band, q));
    EXPECT_EQ(l["rsr"], "camera.csv");
    EXPECT_EQ(l["radiance_w_m2_sr"].get<double>(), 30.0);
    EXPECT_TRUE(l.contains("brightness_temperature_k"));
    EXPECT_FALSE(l.contains("temperature_k"));
}

TEST(PlanckReport, TextStatesTheBandTemperatureAndCelsius) {
    const Band band(8.0, 14.0);
    PlanckQuery q;
    q.band_um = {8.0, 14.0};
    q.temperature_k = 300.0;
    EXPECT_THAT(planck_answer_text(evaluate_planck(band, q)),
                HasSubstr("band 8–14 µm, T = 300.000 K\n"));
    q.temperature_k.reset();
    q.radiance_w_m2_sr = band.radiance(373.15);
    EXPECT_EQ(planck_answer_text(evaluate_planck(band, q)),
              "brightness temperature = 373.1500 K (100.0000 °C)\n");
}

TEST(PlanckReport, BadQuestionsAreErrors) {
    const Band band(8.0, 14.0);
    PlanckQuery q;
    EXPECT_THROW(evaluate_planck(band, q), Error);  // neither
    q.temperature_k = 300.0;
    q.radiance_w_m2_sr = 10.0;
    EXPECT_THROW(evaluate_planck(band, q), Error);  // both
    q.temperature_k.reset();
    q.radiance_w_m2_sr = -1.0;
    EXPECT_THROW(evaluate_planck(band, q), Error);
    q.radiance_w_m2_sr.reset();
    q.temperature_k = -5.0;
    EXPECT_THROW(evaluate_planck(band, q), Error);
}

TEST(PlanckReport, AQuestionFromOptionsNamesTheOptionThatIsWrong) {
    const auto refused_option = [](const PlanckQuery& q) {
        try {
            evaluate_planck(q);
        } catch (const OptionValueError& e) {
            return e.option();
        }
        return std::string();
    };
    PlanckQuery q;
    q.band_um = {14.0, 8.0};
    q.temperature_k = 300.0;
    EXPECT_EQ(refused_option(q), "--band-um");
    q.band_um = {8.0, 14.0};
    q.temperature_k = -5.0;
    EXPECT_EQ(refused_option(q), "--temperature-k");
    q.temperature_k.reset();
    q.radiance_w_m2_sr = -1.0;
    EXPECT_EQ(refused_option(q), "--radiance");
    // The band the options make is the band of the other overload: the same answer.
    const Band band(8.0, 14.0);
    q.radiance_w_m2_sr = band.radiance(300.0);
    EXPECT_EQ(evaluate_planck(q).brightness_temperature_k,
              evaluate_planck(band, q).brightness_temperature_k);
    EXPECT_NEAR(*evaluate_planck(q).brightness_temperature_k, 300.0, 1e-6);
}

}  // namespace
}  // namespace tirpol
