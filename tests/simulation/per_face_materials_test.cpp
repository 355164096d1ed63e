// Per-face materials of mesh files: OBJ `usemtl` (with the .mtl of its `mtllib`) and glTF
// primitives' material indices, mapped by the scene's `materials:` to material library names. Each
// face must render with its own material: a pixel on a face gives the radiance the same pixel gives
// when the whole mesh is that face's material.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <vector>

#include "error_of.h"
#include "scene_fixtures.h"
#include "tirpol/core/error.h"

namespace tirpol::simulation {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using tirpol::test::TempDir;

/// Two 1 m × 1 m quads in the z = 0 plane, facing +z: x ∈ [−1, 0] uses `left`, x ∈ [0, 1] `right`.
void write_two_material_obj(const TempDir& dir, const std::string& left, const std::string& right) {
    tirpol::test::write_text(dir / "two.obj",
                             "mtllib two.mtl\nv -1 -0.5 0\nv 0 -0.5 0\nv 0 0.5 0\nv -1 0.5 0\n"
                             "v 1 -0.5 0\nv 1 0.5 0\nusemtl " +
                                 left + "\nf 1 2 3\nf 1 3 4\nusemtl " + right +
                                 "\nf 2 5 6\nf 2 6 3\n");
    tirpol::test::write_text(dir / "two.mtl",
                             "newmtl " + left + "\nKd 0 0 0\nnewmtl " + right + "\nKd 1 1 1\n");
}

/// A camera 5 m above the quads looking down (image right = +x; 0.23 m per pixel): columns 4–7 see
/// the left quad, 8–11 the right one; rows 3 and 4 lie inside both.
std::string scene_with(const std::string& object_fields) {
    return test::scene_header(16, 8, 16, 4,
                              "fov_deg: 40, position: [0, 0, 5], look_at: [0, 0, 0], up: [0, 1, 0]",
                              "{type: uniform, temperature: 250}") +
           "objects:\n  - {name: two, geometry: {type: mesh, file: two.obj}, " + object_fields +
           ", temperature: 300}\n";
}

std::string error_of(const TempDir& dir, const std::string& yaml) {
    return tirpol::test::error_of([&] { test::load_scene_text(dir, yaml); });
}

/// |a − b| at a pixel in units of its Monte-Carlo standard error.
double sigmas_apart(const Image& a, const Image& b, int x, int y) {
    const double se = std::sqrt(a.at("S0_var", x, y) + b.at("S0_var", x, y));
    return std::abs(a.at("S0", x, y) - b.at("S0", x, y)) / std::max(se, 1e-12);
}

TEST(PerFaceMaterials, ObjUsemtlFacesRenderWithTheirLibraryMaterials) {
    TempDir dir;
    write_two_material_obj(dir, "BlackPaint", "Metal");
    const Scene both = test::load_scene_text(
        dir, scene_with("materials: {BlackPaint: flat_black_paint, Metal: bare_aluminium}"));
    ASSERT_EQ(both.materials.size(), 2u);
    EXPECT_EQ(both.materials[0].name, "flat_black_paint");
    EXPECT_EQ(both.materials[1].name, "bare_aluminium");
    const Image img = render(both);
    const Image black =
        render(test::load_scene_text(dir, scene_with("material: flat_black_paint"), "black.yaml"));
    const Image metal =
        render(test::load_scene_text(dir, scene_with("material: bare_aluminium"), "metal.yaml"));
    for (int y : {3, 4}) {
        for (int x : {4, 6}) {
            EXPECT_LT(sigmas_apart(img, black, x, y), 4.0)
                << "left face (" << x << ", " << y << ")";
            EXPECT_EQ(img.at("material_id", x, y), 0.0f);
        }
        for (int x : {9, 11}) {
            EXPECT_LT(sigmas_apart(img, metal, x, y), 4.0)
                << "right face (" << x << ", " << y << ")";
            EXPECT_EQ(img.at("material_id", x, y), 1.0f);
        }
        // The two materials differ (ε ≈ 0.95 against ≈ 0.03, at 300 K under a 250 K sky): a mesh
        // rendered with one material would fail one of the checks above.
        EXPECT_GT(sigmas_apart(black, metal, 5, y), 10.0);
        EXPECT_EQ(img.at("object_id", 5, y), img.at("object_id", 10, y)) << "one object";
    }
}

/// Writes `<dir>/two.gltf` + `two.bin`: the same two quads as write_two_material_obj, as two
/// primitives whose `material` indices are 1 (left, named "Body") and 0 (right, named `right`).
void write_two_material_gltf(const TempDir& dir, const std::string& right = "Trim") {
    // glTF is y-up: the quads lie in its x–z plane (z = −y of the world), facing +Y (up).
    const std::vector<float> positions = {-1, 0, 0.5f, 0, 0, 0.5f, 0, 0, -0.5f, -1, 0, -0.5f,
                                          0,  0, 0.5f, 1, 0, 0.5f, 1, 0, -0.5f, 0,  0, -0.5f};
    const std::vector<std::uint16_t> indices = {0, 1, 2, 0, 2, 3, 0, 1, 2, 0, 2, 3};
    {
        std::ofstream bin(dir / "two.bin", std::ios::binary);
        bin.write(reinterpret_cast<const char*>(positions.data()),
                  static_cast<std::streamsize>(positions.size() * sizeof(float)));
        bin.write(reinterpret_cast<const char*>(indices.data()),
                  static_cast<std::streamsize>(indices.size() * sizeof(std::uint16_t)));
    }
    const std::string first_material = right.empty() ? "{}" : "{\"name\": \"" + right + "\"}";
    tirpol::test::write_text(dir / "two.gltf", R"({"asset": {"version": "2.0"}, "scene": 0,
"scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
"materials": [)" + first_material + R"(, {"name": "Body"}],
"meshes": [{"primitives": [
  {"attributes": {"POSITION": 0}, "indices": 2, "material": 1},
  {"attributes": {"POSITION": 1}, "indices": 3, "material": 0}]}],
"buffers": [{"uri": "two.bin", "byteLength": 120}],
"bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                {"buffer": 0, "byteOffset": 96, "byteLength": 12},
                {"buffer": 0, "byteOffset": 108, "byteLength": 12}],
"accessors": [
  {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, 0, -0.5], "max": [0, 0, 0.5]},
  {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, -0.5], "max": [1, 0, 0.5]},
  {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"},
  {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}]})");
}

TEST(PerFaceMaterials, GltfPrimitiveMaterialIndicesMapToLibraryNames) {
    TempDir dir;
    write_two_material_gltf(dir);
    std::string yaml = scene_with("materials: {Body: flat_black_paint, Trim: bare_aluminium}");
    yaml.replace(yaml.find("two.obj"), 7, "two.gltf");
    const Scene scene = test::load_scene_text(dir, yaml);
    const SceneObject& two = scene.objects.at(0);
    ASSERT_EQ(two.triangle_materials.size(), 4u);
    // The first primitive (material 1, "Body") is the left quad, the second (material 0, "Trim")
    // the right one.
    EXPECT_EQ(scene.materials[two.material_at(0)].name, "flat_black_paint");
    EXPECT_EQ(scene.materials[two.material_at(3)].name, "bare_aluminium");
    const Image img = render(scene);
    EXPECT_EQ(img.at("material_id", 5, 3), static_cast<float>(two.material_at(0)));
    EXPECT_EQ(img.at("material_id", 10, 4), static_cast<float>(two.material_at(3)));
    EXPECT_GT(img.at("S0", 5, 3), img.at("S0", 10, 4)) << "black paint (left) emits more";

    // An unnamed material cannot be mapped: the error says so and names the file.
    write_two_material_gltf(dir, "");
    try {
        test::load_scene_text(dir, yaml);
        FAIL() << "an unnamed glTF material was mapped";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), AllOf(HasSubstr("two.gltf"), HasSubstr("no name")));
    }
}

TEST(PerFaceMaterials, OneMaterialForTheWholeMeshStillWorks) {
    TempDir dir;
    write_two_material_obj(dir, "BlackPaint", "Metal");
    const Scene scene = test::load_scene_text(dir, scene_with("material: flat_black_paint"));
    EXPECT_TRUE(scene.objects[0].triangle_materials.empty());
    EXPECT_EQ(scene.materials.size(), 1u);
}

TEST(PerFaceMaterials, UnmappedAndUnknownNamesAreErrorsNamingMaterialAndFile) {
    TempDir dir;
    write_two_material_obj(dir, "BlackPaint", "Metal");
    EXPECT_THAT(
        error_of(dir, scene_with("materials: {BlackPaint: flat_black_paint}")),
        AllOf(HasSubstr("scene.yaml:"), HasSubstr("objects[0].materials"), HasSubstr("two.obj"),
              HasSubstr("uses material \"Metal\""), HasSubstr("names: BlackPaint")));
    EXPECT_THAT(error_of(dir, scene_with("materials: {BlackPaint: flat_black_paint, Metal: "
                                         "bare_aluminium, Glas: silica_glass}")),
                AllOf(HasSubstr("objects[0].materials.Glas"), HasSubstr("two.obj"),
                      HasSubstr("has no material \"Glas\""), HasSubstr("BlackPaint, Metal")));
    EXPECT_THAT(error_of(dir, scene_with("materials: {BlackPaint: flat_black_paint, Metal: "
                                         "unobtainium}")),
                AllOf(HasSubstr("objects[0].materials.Metal"), HasSubstr("unknown material"),
                      HasSubstr("unobtainium")));
    EXPECT_THAT(error_of(dir, scene_with("material: flat_black_paint, materials: {BlackPaint: "
                                         "flat_black_paint, Metal: bare_aluminium}")),
                HasSubstr("either `material`"));
    EXPECT_THAT(error_of(dir, scene_with("materials: [flat_black_paint]")),
                HasSubstr("expected a mapping"));
    std::string primitive = scene_with("materials: {a: flat_black_paint}");
    primitive.replace(primitive.find("{type: mesh, file: two.obj}"), 27,
                      "{type: box, size: [1, 1, 1]}");
    EXPECT_THAT(error_of(dir, primitive), HasSubstr("need a mesh file"));
}

TEST(PerFaceMaterials, FacesWithoutAFileMaterialAreNamedAsSuch) {
    // assimp gives faces that no usemtl names its default material: the error says what that name
    // means instead of leaving the user to guess.
    TempDir dir;
    tirpol::test::write_text(dir / "two.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_THAT(error_of(dir, scene_with("materials: {Paint: flat_black_paint}")),
                AllOf(HasSubstr("two.obj"), HasSubstr("\"" + std::string(kNoFileMaterial) + "\""),
                      HasSubstr("without usemtl")));
}

}  // namespace
}  // namespace tirpol::simulation
