// The thermal YAML and the example shipped in config/thermal/.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test_support.h"
#include "tirpol/core/error.h"
#include "tirpol/thermal/civil_time.h"
#include "tirpol/thermal/thermal_config.h"

namespace tirpol::thermal {
namespace {

using ::testing::HasSubstr;

TEST(ThermalConfig, LoadsShippedBallOnSnowExample) {
    const ThermalScene s =
        load_thermal_scene(test::source_dir() / "config/thermal/ball_on_snow_thermal.yaml");
    EXPECT_DOUBLE_EQ(s.site.latitude_deg, 43.16);
    EXPECT_DOUBLE_EQ(s.site.utc_offset_h, -5.0);
    ASSERT_TRUE(s.time_s.has_value());
    EXPECT_DOUBLE_EQ(*s.time_s, parse_time("2026-01-16T13:00-05:00", 0.0));
    ASSERT_EQ(s.materials.size(), 3u);
    EXPECT_EQ(s.materials[1].slab.back.kind, BackBoundary::Kind::Ground);
    EXPECT_DOUBLE_EQ(s.materials[1].slab.back.temperature_k, 273.15);
    ASSERT_EQ(s.objects.size(), 6u);
    EXPECT_EQ(s.objects[2].facet.azimuth_deg, 0.0);
    EXPECT_EQ(s.objects[4].shadow_fraction, 1.0);
    // The paper's Fig. 2 phenomenology on this example: the sunlit ball is warmer than the snow.
    const auto& ball = s.objects[0];
    const auto& field = s.objects[3];
    const double t_ball = predict_surface_temperature(*s.weather, s.materials[ball.material],
                                                      ball.facet, *s.time_s, s.options);
    const double t_snow = predict_surface_temperature(*s.weather, s.materials[field.material],
                                                      field.facet, *s.time_s, s.options);
    EXPECT_GT(t_ball, t_snow + 5.0);
}

TEST(ThermalConfig, ErrorsNameTheField) {
    test::TempDir dir;
    const std::string weather =
        "weather: " + (test::source_dir() / "config/thermal/synthetic_winter.epw").string() + "\n";
    const std::string material =
        "materials:\n  - name: m\n    solar_absorptivity: 0.5\n    thermal_emissivity: 0.9\n"
        "    layers: [{thickness_m: 0.01, conductivity_w_m_k: 1, density_kg_m3: 1000, "
        "specific_heat_j_kg_k: 1000}]\n";
    test::write_text(dir / "a.yaml", weather + material + "objects: [{name: o, material: n}]\n");
    EXPECT_THAT([&] { load_thermal_scene(dir / "a.yaml"); },
                ::testing::ThrowsMessage<Error>(HasSubstr("did you mean 'm'")));
    test::write_text(dir / "b.yaml",
                     weather + material + "objects: [{name: o, material: m, tilt_deg: 200}]\n");
    EXPECT_THAT([&] { load_thermal_scene(dir / "b.yaml"); },
                ::testing::ThrowsMessage<Error>(HasSubstr("tilt_deg")));
    test::write_text(dir / "c.yaml", weather + "thermal: {sky_model: swinbank}\n" + material +
                                         "objects: [{name: o, material: m}]\n");
    EXPECT_THAT([&] { load_thermal_scene(dir / "c.yaml"); },
                ::testing::ThrowsMessage<Error>(HasSubstr("berdahl-martin")));
    test::write_text(dir / "d.yaml",
                     "weather: log.csv\n" + material + "objects: [{name: o, material: m}]\n");
    EXPECT_THAT([&] { load_thermal_scene(dir / "d.yaml"); },
                ::testing::ThrowsMessage<Error>(HasSubstr("needs a `site`")));
}

}  // namespace
}  // namespace tirpol::thermal
