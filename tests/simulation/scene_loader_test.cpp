// Scene files: what the loader accepts and the messages it gives for what it does not.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "error_of.h"
#include "scene_fixtures.h"
#include "temperature_value.h"
#include "tirpol/core/error.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::simulation {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using tirpol::test::TempDir;

std::string good_scene(const std::string& object_extra = "",
                       const std::string& geometry = "{type: sphere, radius: 1}",
                       const std::string& material = test::kSmoothPaint) {
    return test::scene_header(8, 6, 2, 2, "fov_deg: 30, position: [0, -5, 0], look_at: [0, 0, 0]",
                              "{type: uniform, temperature: 250}") +
           "objects:\n"
           "  - name: ball\n"
           "    geometry: " +
           geometry +
           "\n"
           "    material: " +
           material +
           "\n"
           "    temperature: 300\n" +
           object_extra;
}

std::string error_of(const TempDir& dir, const std::string& yaml) {
    return tirpol::test::error_of([&] { test::load_scene_text(dir, yaml); });
}

TEST(SceneLoader, LoadsAValidScene) {
    TempDir dir;
    const Scene scene = test::load_scene_text(dir, good_scene());
    EXPECT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.camera.width(), 8);
    EXPECT_EQ(scene.sampling.seed, 7u);
}

TEST(SceneLoader, UnknownKeyNamesFileLineAndSuggestion) {
    TempDir dir;
    std::string yaml = good_scene();
    yaml.replace(yaml.find("camera:"), 7, "camra:");
    EXPECT_THAT(error_of(dir, yaml),
                AllOf(HasSubstr("scene.yaml:"), HasSubstr("camra"), HasSubstr("camera")));
}

TEST(SceneLoader, EstimatorIsReadAndAnUnknownOneIsNamed) {
    TempDir dir;
    EXPECT_EQ(test::load_scene_text(dir, good_scene()).sampling.estimator,
              Estimator::control_variate);
    std::string yaml = good_scene();
    yaml.replace(yaml.find("seed: 7}"), 8, "seed: 7, estimator: plain}");
    EXPECT_EQ(test::load_scene_text(dir, yaml).sampling.estimator, Estimator::plain);
    yaml.replace(yaml.find("plain"), 5, "mcmc");
    EXPECT_THAT(error_of(dir, yaml),
                AllOf(HasSubstr("scene.yaml:2"), HasSubstr("sampling.estimator"),
                      HasSubstr("expected plain or control-variate, got 'mcmc'")));
}

TEST(SceneLoader, ReplicatesAreReadAndOutOfRangeCountsAreNamed) {
    TempDir dir;
    EXPECT_EQ(test::load_scene_text(dir, good_scene()).sampling.replicates, kDefaultReplicates);
    std::string yaml = good_scene();
    yaml.replace(yaml.find("seed: 7}"), 8, "seed: 7, replicates: 1}");
    EXPECT_EQ(test::load_scene_text(dir, yaml).sampling.replicates, 1);
    yaml.replace(yaml.find("replicates: 1"), 13, "replicates: 0");
    EXPECT_THAT(error_of(dir, yaml),
                AllOf(HasSubstr("scene.yaml:2"), HasSubstr("sampling.replicates"),
                      HasSubstr("expected 1–1024"), HasSubstr("got 0")));
}

TEST(SceneLoader, MissingMeshIsAClearError) {
    TempDir dir;
    EXPECT_THAT(error_of(dir, good_scene("", "{type: mesh, file: no_such_car.obj}")),
                AllOf(HasSubstr("scene.yaml:"), HasSubstr("objects[0].geometry.file"),
                      HasSubstr("mesh file not found"), HasSubstr("no_such_car.obj")));
}

TEST(SceneLoader, MissingMaterialIsAClearError) {
    TempDir dir;
    EXPECT_THAT(error_of(dir, good_scene("", "{type: sphere, radius: 1}", "unobtainium_paint")),
                AllOf(HasSubstr("objects[0].material"),
                      HasSubstr("unknown material \"unobtainium_paint\"")));
    EXPECT_THAT(error_of(dir, good_scene("", "{type: sphere, radius: 1}", "paints/missing.yaml")),
                AllOf(HasSubstr("objects[0].material"), HasSubstr("material file not found")));
}

TEST(SceneLoader, WrongTypeNamesTheField) {
    TempDir dir;
    std::string yaml = good_scene();
    yaml.replace(yaml.find("spp: 2"), 6, "spp: many");
    EXPECT_THAT(error_of(dir, yaml),
                AllOf(HasSubstr("scene.yaml:2"), HasSubstr("sampling.spp"), HasSubstr("many")));
}

TEST(SceneLoader, PredictedTemperatureIsRejectedUntilTheThermalSolverExists) {
    TempDir dir;
    std::string yaml = good_scene();
    yaml.replace(yaml.find("temperature: 300"), 16, "temperature: predicted");
    EXPECT_THAT(error_of(dir, yaml),
                AllOf(HasSubstr("objects[0].temperature"), HasSubstr("thermal solver")));
}

TEST(SceneLoader, SphereNeedsUniformScale) {
    TempDir dir;
    EXPECT_THAT(error_of(dir, good_scene("    transform: {scale: [1, 2, 1]}\n")),
                HasSubstr("uniform scale"));
}

TEST(SceneLoader, CelsiusOnlyWhereWrittenSo) {
    const auto k = [](const std::string& text) {
        return temperature_k_from_config(ConfigNode::parse("t: " + text).at("t"));
    };
    EXPECT_DOUBLE_EQ(k("300"), 300.0);
    EXPECT_DOUBLE_EQ(k("\"15 °C\""), 288.15);
    EXPECT_DOUBLE_EQ(k("\"-5°C\""), 268.15);
    EXPECT_DOUBLE_EQ(k("\"288.15 K\""), 288.15);
    EXPECT_THROW(k("\"15 C\""), Error);
    EXPECT_THROW(k("-3"), Error);
}

TEST(SceneLoader, MeshFilesPerVertexTemperaturesAndPrimitivesLoad) {
    TempDir dir;
    // A 2 m square as OBJ (4 vertices) with one temperature per vertex position.
    tirpol::test::write_text(
        dir / "square.obj",
        "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 1//1 3//1 4//1\n");
    tirpol::test::write_text(
        dir / "square_t.csv",
        "# per-vertex temperatures, by "
        "position\nx,y,z,temperature_k\n-1,-1,0,280\n1,-1,0,300\n1,1,0,320\n-1,1,0,300\n");
    tirpol::test::write_text(dir / "tri.ply",
                             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty "
                             "float y\nproperty float z\n"
                             "element face 1\nproperty list uchar int "
                             "vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    const std::string yaml =
        test::scene_header(9, 9, 1, 0,
                           "fov_deg: 20, position: [0, 0, 10], look_at: [0, 0, 0], up: [0, 1, 0]",
                           "{type: uniform, temperature: 250}") +
        "objects:\n"
        "  - {name: square, geometry: {type: mesh, file: square.obj}, material: " +
        std::string(test::kGreyDiffuse) +
        ", temperature: {vertex_csv: square_t.csv}}\n"
        "  - {name: tri, geometry: {type: mesh, file: tri.ply}, transform: {translate: [0, 0, "
        "-5]}, material: " +
        test::kGreyDiffuse +
        ", temperature: \"20 °C\"}\n"
        "  - {name: box, geometry: {type: box, size: [1, 1, 1]}, transform: {translate: [0, 0, "
        "-9]}, material: " +
        test::kGreyDiffuse +
        ", temperature: 290}\n"
        "  - {name: cyl, geometry: {type: cylinder, radius: 0.5, height: 1}, transform: "
        "{translate: [3, 0, -9], rotate_deg: [90, 0, 0]}, material: " +
        test::kGreyDiffuse +
        ", temperature: 290}\n"
        "  - {name: disk, geometry: {type: disk, radius: 0.5}, transform: {translate: [-3, 0, "
        "-9]}, material: " +
        test::kGreyDiffuse +
        ", temperature: 290}\n"
        "  - {name: plane, geometry: {type: plane, size: [1, 1]}, transform: {translate: [-3, 3, "
        "-9], scale: 2}, material: " +
        test::kGreyDiffuse + ", temperature: 290}\n";
    const Scene scene = test::load_scene_text(dir, yaml);
    ASSERT_EQ(scene.objects.size(), 6u);
    EXPECT_EQ(scene.materials.size(), 6u) << "every inline material is its own entry";
    const Image img = render(scene);
    // Centre pixel of a 9×9 image hits the square's centre: bilinear mean of the four corners (300
    // K).
    EXPECT_NEAR(img.at("temperature_k", 4, 4), 300.0, 1e-3);
    // Pixel (2, 6) looks at (−0.78, −0.78), on the diagonal from vertex 1 (280 K) to vertex 3 (320
    // K): linear interpolation gives 280 + 40·0.11 = 284.4 K.
    EXPECT_NEAR(img.at("temperature_k", 2, 6), 284.4, 0.3);
    EXPECT_EQ(img.at("object_id", 4, 4), 0.0f);
}

}  // namespace
}  // namespace tirpol::simulation
