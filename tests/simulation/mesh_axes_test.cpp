// Mesh file axes: glTF 2.0 is y-up (Khronos glTF 2.0.1 specification, section 3.4 "Coordinate
// System and Units": +Y up, +Z forward, −X right), tirpol's world is z-up. A glTF whose geometry
// is known must come in upright; OBJ and PLY have no convention and stay as written unless the
// scene's `up_axis` says otherwise.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <vector>

#include "scene_fixtures.h"
#include "tirpol/core/error.h"

namespace tirpol::simulation {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using tirpol::test::TempDir;

/// Writes `<dir>/<stem>.gltf` + `<stem>.bin`: one quad x ∈ [−w/2, w/2], y ∈ [0, h] in the z = 0
/// plane of the glTF's axes, counter-clockwise seen from +Z (its front faces glTF's forward).
void write_gltf_quad(const TempDir& dir, const std::string& stem, float w, float h) {
    const std::vector<float> positions = {-w / 2, 0, 0, w / 2, 0, 0, w / 2, h, 0, -w / 2, h, 0};
    const std::vector<std::uint16_t> indices = {0, 1, 2, 0, 2, 3};
    {
        std::ofstream bin(dir / (stem + ".bin"), std::ios::binary);
        bin.write(reinterpret_cast<const char*>(positions.data()),
                  static_cast<std::streamsize>(positions.size() * sizeof(float)));
        bin.write(reinterpret_cast<const char*>(indices.data()),
                  static_cast<std::streamsize>(indices.size() * sizeof(std::uint16_t)));
    }
    tirpol::test::write_text(
        dir / (stem + ".gltf"),
        fmt::format(R"({{"asset": {{"version": "2.0"}}, "scene": 0, "scenes": [{{"nodes": [0]}}],
"nodes": [{{"mesh": 0}}],
"meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1}}]}}],
"buffers": [{{"uri": "{}.bin", "byteLength": 60}}],
"bufferViews": [{{"buffer": 0, "byteOffset": 0, "byteLength": 48}},
                {{"buffer": 0, "byteOffset": 48, "byteLength": 12}}],
"accessors": [{{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                "min": [{}, 0, 0], "max": [{}, {}, 0]}},
              {{"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}}]}})",
                    stem, -w / 2, w / 2, h));
}

std::string one_mesh_scene(const std::string& geometry) {
    return test::scene_header(80, 80, 1, 0, "fov_deg: 30, position: [0, -5, 1], look_at: [0, 0, 1]",
                              "{type: uniform, temperature: 250}") +
           "objects:\n  - {name: board, geometry: " + geometry +
           ", material: " + test::kGreyDiffuse + ", temperature: 300}\n";
}

/// Edge lengths of the mesh's axis-aligned bounding box, m.
Vec3 extent_of(const TriangleMesh& mesh) {
    Vec3 lo = mesh.positions[0], hi = mesh.positions[0];
    for (const auto& p : mesh.positions) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    return hi - lo;
}

TEST(MeshAxes, GltfComesInUprightFacingSouth) {
    TempDir dir;
    write_gltf_quad(dir, "quad", 0.5f, 2.0f);
    const Scene scene = test::load_scene_text(dir, one_mesh_scene("{type: mesh, file: quad.gltf}"));
    const TriangleMesh& mesh = scene.tracer->mesh(0);
    ASSERT_EQ(mesh.positions.size(), 4u);
    // glTF +Y (the quad's 2 m height) is world +z; nothing extends along world y.
    const Vec3 extent = extent_of(mesh);
    EXPECT_NEAR(extent.x(), 0.5, 1e-6);
    EXPECT_NEAR(extent.y(), 0.0, 1e-6);
    EXPECT_NEAR(extent.z(), 2.0, 1e-6);
    for (const auto& p : mesh.positions) EXPECT_GE(p.z(), -1e-6) << "upright from z = 0 up";
    // The front (+Z in glTF, the counter-clockwise side) faces world −y.
    for (const auto& n : mesh.normals) EXPECT_NEAR(n.dot(-Vec3::UnitY()), 1.0, 1e-6);
    const auto& tri = mesh.triangles[0];
    const Vec3 face = (mesh.positions[tri[1]] - mesh.positions[tri[0]])
                          .cross(mesh.positions[tri[2]] - mesh.positions[tri[0]]);
    EXPECT_LT(face.y(), 0.0) << "winding stays counter-clockwise seen from the front";
}

/// Rows and columns spanned by the object's pixels in the object_id channel.
std::pair<int, int> rows_and_columns_of(const Image& img, float id) {
    int x0 = img.width(), x1 = -1, y0 = img.height(), y1 = -1;
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x)
            if (img.at("object_id", x, y) == id)
                x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y),
                y1 = std::max(y1, y);
    return {y1 - y0 + 1, x1 - x0 + 1};
}

TEST(MeshAxes, GltfRendersUpright) {
    // A 0.5 m wide, 2 m tall board seen level from 5 m to the south: upright, it fills a tall
    // narrow patch (2/0.5 = 4 times as many rows as columns); lying on its side (glTF's y taken as
    // north) it would be seen edge-on as a thin horizontal line at the camera's feet.
    TempDir dir;
    write_gltf_quad(dir, "board", 0.5f, 2.0f);
    const Scene scene =
        test::load_scene_text(dir, one_mesh_scene("{type: mesh, file: board.gltf}"));
    const Image img = render(scene);
    const auto [rows, columns] = rows_and_columns_of(img, 0.0f);
    ASSERT_GT(columns, 0) << "the board is in view";
    EXPECT_NEAR(static_cast<double>(rows) / columns, 4.0, 0.4);
    // It spans z = 0 to 2 m, 1 m either side of the camera's level line (image row 40; 30 px/m at
    // 5 m with a 30° field of view over 80 px): rows 10 to 70.
    EXPECT_EQ(img.at("object_id", 40, 15), 0.0f);
    EXPECT_EQ(img.at("object_id", 40, 65), 0.0f);
    // Seen from its front: its visible normal points at the camera (−y).
    EXPECT_LT(img.at("normal_y", 40, 40), -0.99f);
}

TEST(MeshAxes, ObjStaysAsWrittenAndUpAxisOverrideConverts) {
    TempDir dir;
    // A quad 2 m along y: z-up as written (lying flat), or upright if the file is y-up.
    tirpol::test::write_text(
        dir / "quad.obj", "v -0.25 0 0\nv 0.25 0 0\nv 0.25 2 0\nv -0.25 2 0\nf 1 2 3\nf 1 3 4\n");
    const Scene as_written =
        test::load_scene_text(dir, one_mesh_scene("{type: mesh, file: quad.obj}"));
    EXPECT_NEAR(extent_of(as_written.tracer->mesh(0)).y(), 2.0, 1e-6);
    EXPECT_NEAR(extent_of(as_written.tracer->mesh(0)).z(), 0.0, 1e-6);
    const Scene y_up =
        test::load_scene_text(dir, one_mesh_scene("{type: mesh, file: quad.obj, up_axis: y}"));
    EXPECT_NEAR(extent_of(y_up.tracer->mesh(0)).y(), 0.0, 1e-6);
    EXPECT_NEAR(extent_of(y_up.tracer->mesh(0)).z(), 2.0, 1e-6);
    // And a glTF can be declared z-up (a file written by a tool that ignores the convention).
    write_gltf_quad(dir, "flat", 0.5f, 2.0f);
    const Scene z_up =
        test::load_scene_text(dir, one_mesh_scene("{type: mesh, file: flat.gltf, up_axis: z}"));
    EXPECT_NEAR(extent_of(z_up.tracer->mesh(0)).y(), 2.0, 1e-6);
}

TEST(MeshAxes, ObjectTransformActsAfterTheAxisConversion) {
    // rotate_deg and translate are in the world: a 90° turn about z of the upright glTF board
    // leaves it upright (and turns its front from −y to +x).
    TempDir dir;
    write_gltf_quad(dir, "quad", 0.5f, 2.0f);
    const Scene scene = test::load_scene_text(
        dir, one_mesh_scene("{type: mesh, file: quad.gltf}, transform: {rotate_deg: [0, 0, 90], "
                            "translate: [0, 0, 1]}"));
    const TriangleMesh& mesh = scene.tracer->mesh(0);
    const Vec3 extent = extent_of(mesh);
    EXPECT_NEAR(extent.z(), 2.0, 1e-6);
    EXPECT_NEAR(extent.y(), 0.5, 1e-6);
    for (const auto& p : mesh.positions) EXPECT_GE(p.z(), 1.0 - 1e-6);
    for (const auto& n : mesh.normals) EXPECT_NEAR(n.x(), 1.0, 1e-6);
}

TEST(MeshAxes, BadUpAxisNamesTheFieldAndWhatIsExpected) {
    TempDir dir;
    write_gltf_quad(dir, "quad", 0.5f, 2.0f);
    try {
        test::load_scene_text(dir, one_mesh_scene("{type: mesh, file: quad.gltf, up_axis: x}"));
        FAIL() << "up_axis: x was accepted";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), AllOf(HasSubstr("scene.yaml:"), HasSubstr("up_axis"),
                                    HasSubstr("expected y or z"), HasSubstr("\"x\"")));
    }
    EXPECT_THROW(test::load_scene_text(dir, one_mesh_scene("{type: box, size: [1, 1, 1], "
                                                           "up_axis: y}")),
                 Error)
        << "up_axis belongs to mesh files only";
}

}  // namespace
}  // namespace tirpol::simulation
