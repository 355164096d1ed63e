#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>

#include "tirpol/core/error.h"
#include "tirpol/simulation/ray_tracer.h"

namespace tirpol::simulation {

Mat3 Transform::rotation_from_euler_deg(const Vec3& angles_deg) {
    using Eigen::AngleAxisd;
    return (AngleAxisd(deg_to_rad(angles_deg.z()), Vec3::UnitZ()) *
            AngleAxisd(deg_to_rad(angles_deg.y()), Vec3::UnitY()) *
            AngleAxisd(deg_to_rad(angles_deg.x()), Vec3::UnitX()))
        .toRotationMatrix();
}

void transform_mesh(TriangleMesh& mesh, const Transform& t) {
    for (auto& p : mesh.positions) p = t.point(p);
    for (auto& n : mesh.normals) n = t.normal(n);
    // A mirroring scale flips the winding; keep triangles counter-clockwise from outside.
    if (t.scale.prod() < 0.0)
        for (auto& tri : mesh.triangles) std::swap(tri[1], tri[2]);
}

namespace {
void add_quad(TriangleMesh& m, const Vec3& origin, const Vec3& du, const Vec3& dv) {
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    const Vec3 n = du.cross(dv).normalized();
    const Vec3 corners[4] = {origin, origin + du, origin + du + dv, origin + dv};
    const Eigen::Vector2d uv[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int i = 0; i < 4; ++i) {
        m.positions.push_back(corners[i]);
        m.normals.push_back(n);
        m.uvs.push_back(uv[i]);
    }
    m.triangles.push_back({base, base + 1, base + 2});
    m.triangles.push_back({base, base + 2, base + 3});
}
}  // namespace

TriangleMesh make_box(const Vec3& size) {
    TriangleMesh m;
    const Vec3 h = 0.5 * size;
    const Vec3 x(size.x(), 0, 0), y(0, size.y(), 0), z(0, 0, size.z());
    add_quad(m, Vec3(-h.x(), -h.y(), -h.z()), y, x);  // bottom, normal −z
    add_quad(m, Vec3(-h.x(), -h.y(), h.z()), x, y);   // top, +z
    add_quad(m, Vec3(-h.x(), -h.y(), -h.z()), x, z);  // south, −y
    add_quad(m, Vec3(-h.x(), h.y(), -h.z()), z, x);   // north, +y
    add_quad(m, Vec3(-h.x(), -h.y(), -h.z()), z, y);  // west, −x
    add_quad(m, Vec3(h.x(), -h.y(), -h.z()), y, z);   // east, +x
    return m;
}

TriangleMesh make_plane(double size_x, double size_y) {
    TriangleMesh m;
    add_quad(m, Vec3(-0.5 * size_x, -0.5 * size_y, 0.0), Vec3(size_x, 0, 0), Vec3(0, size_y, 0));
    return m;
}

TriangleMesh make_disk(double radius, int segments) {
    TriangleMesh m;
    m.positions.push_back(Vec3::Zero());
    m.normals.push_back(Vec3::UnitZ());
    m.uvs.emplace_back(0.5, 0.5);
    const auto n = static_cast<std::uint32_t>(segments);
    for (std::uint32_t i = 0; i < n; ++i) {
        const double a = 2.0 * kPi * i / n;
        m.positions.emplace_back(radius * std::cos(a), radius * std::sin(a), 0.0);
        m.normals.push_back(Vec3::UnitZ());
        m.uvs.emplace_back(0.5 + 0.5 * std::cos(a), 0.5 + 0.5 * std::sin(a));
        m.triangles.push_back({0, 1 + i, 1 + (i + 1) % n});
    }
    return m;
}

TriangleMesh make_cylinder(double radius, double height, int segments, bool caps) {
    TriangleMesh m;
    const auto n = static_cast<std::uint32_t>(segments);
    for (std::uint32_t i = 0; i <= n; ++i) {
        const double a = 2.0 * kPi * i / n;
        const Vec3 radial(std::cos(a), std::sin(a), 0.0);
        for (int k = 0; k < 2; ++k) {
            m.positions.push_back(radius * radial + Vec3(0, 0, (k - 0.5) * height));
            m.normals.push_back(radial);
            m.uvs.emplace_back(static_cast<double>(i) / n, k);
        }
    }
    for (std::uint32_t i = 0; i < n; ++i) {
        const std::uint32_t a = 2 * i, b = 2 * i + 1, c = 2 * i + 2, d = 2 * i + 3;
        m.triangles.push_back({a, c, d});
        m.triangles.push_back({a, d, b});
    }
    if (caps) {
        for (int k = 0; k < 2; ++k) {
            TriangleMesh cap = make_disk(radius, segments);
            const double sign = k == 0 ? -1.0 : 1.0;
            Transform t;
            t.translate = Vec3(0, 0, sign * 0.5 * height);
            if (k == 0) t.rotation = Transform::rotation_from_euler_deg(Vec3(180, 0, 0));
            transform_mesh(cap, t);
            const auto base = static_cast<std::uint32_t>(m.positions.size());
            m.positions.insert(m.positions.end(), cap.positions.begin(), cap.positions.end());
            m.normals.insert(m.normals.end(), cap.normals.begin(), cap.normals.end());
            m.uvs.insert(m.uvs.end(), cap.uvs.begin(), cap.uvs.end());
            for (const auto& tri : cap.triangles)
                m.triangles.push_back({base + tri[0], base + tri[1], base + tri[2]});
        }
    }
    return m;
}

namespace {
/// The name a file gives material `index`; empty if it has none.
std::string material_name(const aiScene& scene, unsigned index) {
    aiString name;
    if (index < scene.mNumMaterials &&
        scene.mMaterials[index]->Get(AI_MATKEY_NAME, name) == aiReturn_SUCCESS)
        return name.C_Str();
    return {};
}
}  // namespace

MeshFile read_mesh_file(const std::filesystem::path& path) {
    if (!std::filesystem::is_regular_file(path)) fail("mesh file not found: {}", path.string());
    Assimp::Importer importer;
    // No vertex joining or re-ordering: per-vertex data files refer to the file's vertex order.
    const aiScene* scene = importer.ReadFile(
        path.string(), aiProcess_Triangulate | aiProcess_GenNormals |
                           aiProcess_PreTransformVertices | aiProcess_SortByPType);
    if (!scene) fail("cannot read mesh {}: {}", path.string(), importer.GetErrorString());
    MeshFile out;
    TriangleMesh& m = out.mesh;
    for (unsigned mi = 0; mi < scene->mNumMeshes; ++mi) {
        const aiMesh* mesh = scene->mMeshes[mi];
        if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
        const std::string name = material_name(*scene, mesh->mMaterialIndex);
        auto it = std::find(out.material_names.begin(), out.material_names.end(), name);
        if (it == out.material_names.end()) it = out.material_names.insert(it, name);
        const auto material = static_cast<std::uint32_t>(it - out.material_names.begin());
        const auto base = static_cast<std::uint32_t>(m.positions.size());
        for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
            const aiVector3D& p = mesh->mVertices[v];
            m.positions.emplace_back(p.x, p.y, p.z);
            const aiVector3D n = mesh->HasNormals() ? mesh->mNormals[v] : aiVector3D(0, 0, 1);
            m.normals.push_back(Vec3(n.x, n.y, n.z).normalized());
            if (mesh->HasTextureCoords(0))
                m.uvs.emplace_back(mesh->mTextureCoords[0][v].x, mesh->mTextureCoords[0][v].y);
            else
                m.uvs.emplace_back(0.0, 0.0);
        }
        for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
            const aiFace& face = mesh->mFaces[f];
            if (face.mNumIndices != 3) continue;
            m.triangles.push_back(
                {base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2]});
            out.triangle_material.push_back(material);
        }
    }
    if (m.triangles.empty()) fail("mesh {} has no triangles", path.string());
    return out;
}

TriangleMesh load_mesh_file(const std::filesystem::path& path) { return read_mesh_file(path).mesh; }

std::optional<UpAxis> up_axis_from_name(std::string_view name) {
    if (name == "y") return UpAxis::y;
    if (name == "z") return UpAxis::z;
    return std::nullopt;
}

UpAxis default_up_axis(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".gltf" || ext == ".glb" ? UpAxis::y : UpAxis::z;
}

Mat3 z_up_rotation(UpAxis axis) {
    if (axis == UpAxis::z) return Mat3::Identity();
    Mat3 r;
    r << 1, 0, 0, 0, 0, -1, 0, 1, 0;
    return r;
}

}  // namespace tirpol::simulation
