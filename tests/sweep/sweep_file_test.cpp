// The sweep file: parameters checked against the base scene, points and seeds, bad input named by
// file:line with "did you mean".

#include <gtest/gtest.h>

#include <set>

#include "test_support.h"
#include "tirpol/core/error.h"
#include "tirpol/simulation/scene.h"
#include "tirpol/sweep/sweep_run.h"

namespace tirpol::sweep {
namespace {

using test::TempDir;

std::string scene_path(const std::string& name) {
    return (test::source_dir() / "config" / "scenes" / name).string();
}

std::filesystem::path write_sweep(const TempDir& dir, const std::string& body) {
    const auto path = dir / "sweep.yaml";
    test::write_text(path, "scene: " + scene_path("ball_on_snow_night.yaml") + "\n" + body);
    return path;
}

std::string load_error(const std::filesystem::path& path) {
    try {
        load_sweep(path);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(SweepFile, GridPointsVaryTheLastAxisFastestWithDistinctDeterministicSeeds) {
    TempDir dir;
    const auto path = write_sweep(dir, R"(axes:
  camera.fov_deg: [20, 30, 40]
  sampling.spp: {from: 2, to: 4, step: 2}
)");
    const SweepSpec spec = load_sweep(path);
    const auto points = sweep_points(spec);
    ASSERT_EQ(points.size(), 6u);
    EXPECT_EQ(points[1].value_index, (std::vector<std::size_t>{0, 1}));
    EXPECT_EQ(points[2].value_index, (std::vector<std::size_t>{1, 0}));
    EXPECT_EQ(points[5].id, "p0005");
    EXPECT_EQ(spec.axes[1].labels, (std::vector<std::string>{"2", "4"}));
    std::set<std::uint64_t> seeds;
    for (const auto& p : points) {
        seeds.insert(p.seed);
        EXPECT_EQ(p.seed, point_seed(1, p.index));
        EXPECT_LT(p.seed, 1ULL << 63);
    }
    EXPECT_EQ(seeds.size(), points.size());
    EXPECT_NE(point_seed(2, 0), point_seed(1, 0));
}

TEST(SweepFile, ListCombinesTheIthValuesAndNeedsEqualLengths) {
    TempDir dir;
    auto path = write_sweep(dir, R"(combine: list
axes:
  camera.fov_deg: [20, 30]
  sampling.spp: [2, 4]
)");
    EXPECT_EQ(sweep_points(load_sweep(path)).size(), 2u);
    path = write_sweep(dir, R"(combine: list
axes:
  camera.fov_deg: [20, 30]
  sampling.spp: [2, 4, 8]
)");
    EXPECT_NE(load_error(path).find("equal length"), std::string::npos) << load_error(path);
}

TEST(SweepFile, PointSceneIsTheBaseWithItsOverridesReadByTheSceneLoader) {
    TempDir dir;
    const auto path = write_sweep(dir, R"(set:
  camera.resolution: [32, 24]
axes:
  camera.position: [[0, -3.2, 1.1], [1.5, -3, 1.1]]
  objects[ball].temperature: ["2 °C", "20 °C"]
  materials.glossy_black_paint.parameters.sigma: [0.05, 0.3]
  band: [{lo_um: 8, hi_um: 14}, {lo_um: 3, hi_um: 5}]
)");
    const SweepSpec spec = load_sweep(path);
    const auto points = sweep_points(spec);
    ASSERT_EQ(points.size(), 16u);
    const SweepPoint& last = points.back();
    const simulation::Scene scene = simulation::load_scene(point_config(spec, last).scene);
    EXPECT_EQ(scene.camera.width(), 32);
    EXPECT_NEAR(scene.camera.position().x(), 1.5, 1e-12);
    EXPECT_NEAR(scene.band.lo_um(), 3.0, 1e-12);
    EXPECT_NEAR(scene.objects[1].temperature.min_k(), 293.15, 1e-9);
    // The library material became inline with the swept roughness; relative paths still resolve.
    const ConfigNode ball_material =
        point_config(spec, last).scene.at("objects").elements()[1].at("material");
    EXPECT_NEAR(ball_material.at("parameters").get<double>("sigma"), 0.3, 1e-12);
    EXPECT_EQ(ball_material.get<std::string>("model"), "microfacet");
    EXPECT_EQ(spec.scene.at("objects").elements()[1].at("material").as<std::string>(),
              "glossy_black_paint")
        << "the base scene is never modified";
}

TEST(SweepFile, InlinedLibraryMaterialKeepsItsRefractiveIndexTable) {
    // snow.yaml reads its n, k from data/… next to it; inline in the scene the path must still find
    // it.
    TempDir dir;
    const auto path = write_sweep(dir, "axes:\n  materials.snow.parameters.sigma: [0.1, 0.4]\n");
    const SweepSpec spec = load_sweep(path);
    const auto points = sweep_points(spec);
    const simulation::Scene scene = simulation::load_scene(point_config(spec, points[1]).scene);
    EXPECT_EQ(scene.objects[0].name, "snow");
    const ConfigNode snow =
        point_config(spec, points[1]).scene.at("objects").elements()[0].at("material");
    EXPECT_TRUE(
        std::filesystem::path(snow.at("refractive_index").get<std::string>("file")).is_absolute());
    EXPECT_NEAR(snow.at("parameters").get<double>("sigma"), 0.4, 1e-12);
}

TEST(SweepFile, UnknownParameterIsNamedWithFileLineAndSuggestion) {
    TempDir dir;
    const auto path = write_sweep(dir, "axes:\n  camera.positon: [[0, -3, 1]]\n");
    const std::string e = load_error(path);
    EXPECT_NE(e.find("sweep.yaml:3:"), std::string::npos) << e;  // line 1 is `scene:`
    EXPECT_NE(e.find("unknown parameter 'camera.positon'"), std::string::npos) << e;
    EXPECT_NE(e.find("did you mean 'position'?"), std::string::npos) << e;
    const std::string material = load_error(
        write_sweep(dir, "axes:\n  materials.glosy_black_paint.parameters.sigma: [0.1]\n"));
    EXPECT_NE(material.find("did you mean 'glossy_black_paint'?"), std::string::npos) << material;
    const std::string sensor =
        load_error(write_sweep(dir, "axes:\n  sensor.counts.nedt_k: [0.1]\n"));
    EXPECT_NE(sensor.find("no `sensor:` file"), std::string::npos) << sensor;
}

TEST(SweepFile, EmptyAxisAndBadStructureAreClearErrors) {
    TempDir dir;
    const std::string empty = load_error(write_sweep(dir, "axes:\n  camera.fov_deg: []\n"));
    EXPECT_NE(empty.find("sweep.yaml:3:19"), std::string::npos) << empty;
    EXPECT_NE(empty.find("no values"), std::string::npos) << empty;
    EXPECT_NE(load_error(write_sweep(dir, "axes: {}\n")).find("at least one axis"),
              std::string::npos);
    EXPECT_NE(load_error(write_sweep(dir, "axis:\n  camera.fov_deg: [20]\n"))
                  .find("did you mean 'axes'?"),
              std::string::npos);
    EXPECT_NE(
        load_error(
            write_sweep(
                dir, "axes:\n  time: {from: 2026-01-16T00:00, to: 2026-01-15T00:00, step_h: 1}\n"))
            .find("expected `to` ≥ `from`"),
        std::string::npos);
    const std::string region = load_error(
        write_sweep(dir, "axes:\n  camera.fov_deg: [20]\nregions:\n  b: {object: bal}\n"));
    EXPECT_NE(region.find("sweep.yaml:5:"), std::string::npos) << region;
    EXPECT_NE(region.find("did you mean 'ball'?"), std::string::npos) << region;
    const std::string contrast = load_error(
        write_sweep(dir, "axes:\n  camera.fov_deg: [20]\ncontrasts:\n  c: {a: ball, b: snoww}\n"));
    EXPECT_NE(contrast.find("did you mean 'snow'?"), std::string::npos) << contrast;
}

TEST(SweepFile, TimeRangeGivesLocalTimesAndHourCoordinates) {
    TempDir dir;
    test::write_text(
        dir / "sweep.yaml",
        "scene: " +
            (test::source_dir() / "config/thermal/ball_on_snow_day_predicted.yaml").string() +
            "\naxes:\n  time: {from: 2026-01-16T22:00, to: 2026-01-17T02:00, step_h: 2}\n");
    const SweepSpec spec = load_sweep(dir / "sweep.yaml");
    EXPECT_EQ(spec.axes[0].labels, (std::vector<std::string>{"2026-01-16T22:00", "2026-01-17T00:00",
                                                             "2026-01-17T02:00"}));
    EXPECT_EQ(spec.axes[0].coordinates, (std::vector<double>{0.0, 2.0, 4.0}));
}

}  // namespace
}  // namespace tirpol::sweep
