// The thermal model inside a scene: predicted temperatures, and the sky and sun taken from the same
// weather record. As in paper Fig. 2: in the day scene the ball is warmer
// than the snow.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "scene_thermal.h"
#include "test_support.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/config.h"
#include "tirpol/core/error.h"
#include "tirpol/simulation/scene.h"
#include "tirpol/thermal/civil_time.h"
#include "tirpol/thermal/solar_position.h"

namespace tirpol::simulation {
namespace {

TEST(ThermalScene, BallOnSnowDayPredictsBallWarmerThanSnowAndSkyFromWeather) {
    const Scene scene =
        load_scene(test::source_dir() / "config/thermal/ball_on_snow_day_predicted.yaml");
    ASSERT_EQ(scene.objects.size(), 3u);
    const auto& snow = scene.objects[0].temperature;
    const auto& ball = scene.objects[1].temperature;
    EXPECT_GT(ball.max_k(), snow.max_k() + 10.0);  // sunlit side of the ball
    EXPECT_GT(ball.max_k() - ball.min_k(), 10.0);  // the shaded side is much colder
    EXPECT_LT(snow.max_k(), 273.15);               // snow stays frozen
    // Sun from the SPA for the scene's time and site (Rochester, 2026-01-16 10:30 −05:00).
    ASSERT_TRUE(scene.sun.has_value());
    thermal::SpaInput in;
    in.unix_seconds = thermal::parse_time("2026-01-16T10:30-05:00", 0.0);
    in.latitude_deg = 43.16;
    in.longitude_deg = -77.61;
    in.elevation_m = 169.0;
    const Vec3 expected = thermal::sun_direction(thermal::solar_position(in));
    EXPECT_GT(scene.sun->direction.dot(expected), std::cos(deg_to_rad(0.05)));
    EXPECT_GT(scene.sun->transmittance, 0.3);
    // Sky: clear, colder than the air towards the zenith, black at the horizon.
    EXPECT_LT(scene.sky.emissivity(1.0), 0.5);
    EXPECT_NEAR(scene.sky.emissivity(0.0), 1.0, 1e-9);
}

TEST(ThermalScene, PredictedWithoutWeatherOrUnknownThermalMaterialIsAnError) {
    test::TempDir dir;
    const std::string base =
        "band: {lo_um: 8, hi_um: 14}\ncamera: {resolution: [8, 8], fov_deg: 20, position: [0, -3, "
        "1], look_at: [0, 0, 0]}\n"
        "materials_dir: " +
        (test::source_dir() / "config/materials").string() + "\n";
    test::write_text(dir / "a.yaml", base +
                                         "sky: {type: uniform, temperature: 270}\n"
                                         "objects: [{geometry: {type: plane, size: [1, 1]}, "
                                         "material: snow, temperature: predicted}]\n");
    EXPECT_THAT([&] { load_scene(dir / "a.yaml"); },
                ::testing::ThrowsMessage<Error>(::testing::HasSubstr("weather")));
    test::write_text(
        dir / "b.yaml",
        base + "weather: " + (test::source_dir() / "config/thermal/synthetic_winter.epw").string() +
            "\ntime: 2026-01-16T10:30\n"
            "objects: [{geometry: {type: plane, size: [1, 1]}, material: snow, temperature: "
            "predicted}]\n");
    EXPECT_THAT(
        [&] { load_scene(dir / "b.yaml"); },
        ::testing::ThrowsMessage<Error>(::testing::HasSubstr("no thermal material 'snow'")));
}

TEST(ThermalScene, ExportedTemperaturesImportBackUnchanged) {
    // Export in the renderer's import forms ({vertex_csv} for meshes, {texture} EXR for spheres),
    // then load a copy of the scene that reads them instead of predicting: the fields must match.
    const auto path = test::source_dir() / "config/thermal/ball_on_snow_day_predicted.yaml";
    const ConfigNode root = ConfigNode::load_file(path);
    const Scene predicted = load_scene(path);
    test::TempDir dir;
    const auto files = export_scene_temperatures(root, predicted, dir.path());
    ASSERT_EQ(files.size(), 3u);
    std::string yaml = read_file(path);
    const auto replace = [&](const std::string& from, const std::string& to) {
        const auto at = yaml.find(from);
        ASSERT_NE(at, std::string::npos) << from;
        yaml.replace(at, from.size(), to);
    };
    replace("material: snow, temperature: predicted",
            "material: snow, temperature: {vertex_csv: " + (dir / "snow.csv").string() + "}");
    replace("material: glossy_black_paint, temperature: predicted",
            "material: glossy_black_paint, temperature: {texture: " + (dir / "ball.exr").string() +
                "}");
    replace("materials_dir: ../materials",
            "materials_dir: " + (test::source_dir() / "config/materials").string());
    replace("weather: synthetic_winter.epw",
            "weather: " + (test::source_dir() / "config/thermal/synthetic_winter.epw").string());
    test::write_text(dir / "imported.yaml", yaml);
    const Scene imported = load_scene(dir / "imported.yaml");
    for (std::size_t i : {0u, 1u}) {
        EXPECT_NEAR(imported.objects[i].temperature.min_k(),
                    predicted.objects[i].temperature.min_k(), 1e-5)
            << i;
        EXPECT_NEAR(imported.objects[i].temperature.max_k(),
                    predicted.objects[i].temperature.max_k(), 1e-5)
            << i;
    }
}

}  // namespace
}  // namespace tirpol::simulation
