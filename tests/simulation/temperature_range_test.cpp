// Scene temperatures are held to the physical range tirpol accepts, [1, 10000] K (before: 1e9 °C
// rendered without complaint).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "temperature_value.h"
#include "test_support.h"
#include "tirpol/core/config.h"
#include "tirpol/core/error.h"
#include "tirpol/simulation/scene.h"

namespace tirpol::simulation {
namespace {

double parse(const std::string& yaml) {
    return temperature_k_from_config(ConfigNode::parse(yaml, "s.yaml").at("t"));
}

TEST(TemperatureRange, CelsiusKelvinAndBareNumbersInRangeAreAccepted) {
    EXPECT_DOUBLE_EQ(parse("t: \"15 °C\""), 288.15);
    EXPECT_DOUBLE_EQ(parse("t: 5778"), 5778.0);  // the Sun's photosphere
}

TEST(TemperatureRange, OutOfRangeTemperaturesNameTheFieldAndTheRange) {
    for (const char* text : {"t: \"1e9 °C\"", "t: 0.5", "t: \"-300 °C\"", "t: 1e300"}) {
        try {
            parse(text);
            ADD_FAILURE() << text;
        } catch (const Error& e) {
            EXPECT_THAT(
                e.what(),
                testing::AllOf(testing::HasSubstr("s.yaml:1:4: t:"),
                               testing::HasSubstr("outside the physical range [1, 10000] K")))
                << text;
        }
    }
}

TEST(TemperatureRange, SceneFileWithOneBillionCelsiusIsRefused) {
    const auto path = tirpol::test::source_dir() /
                      "tests/data/fuzz-regressions/scene_yaml/temperature_1e9_celsius.yaml";
    try {
        load_scene(path);
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), testing::HasSubstr("temperature_1e9_celsius.yaml"));
    }
}

}  // namespace
}  // namespace tirpol::simulation
