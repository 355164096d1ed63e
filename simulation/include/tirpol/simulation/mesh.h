#pragma once
/// \file mesh.h
/// Triangle meshes of scene objects: procedural primitives and files read through assimp.

#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "tirpol/core/geometry.h"

namespace tirpol::simulation {

/// Indexed triangles with per-vertex normals (unit, outward) and texture coordinates.
struct TriangleMesh {
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;
    std::vector<Eigen::Vector2d> uvs;
    std::vector<std::array<std::uint32_t, 3>> triangles;  ///< counter-clockwise seen from outside
};

/// An affine placement x ↦ R·diag(s)·x + t (scale first, then rotation, then translation).
struct Transform {
    Vec3 translate = Vec3::Zero();
    Mat3 rotation = Mat3::Identity();
    Vec3 scale = Vec3::Ones();

    /// Rotation from `rotate_deg: [rx, ry, rz]`: about x, then y, then z (fixed world axes), R =
    /// Rz·Ry·Rx.
    static Mat3 rotation_from_euler_deg(const Vec3& angles_deg);
    Vec3 point(const Vec3& p) const { return rotation * scale.cwiseProduct(p) + translate; }
    /// Normals transform with the inverse transpose: R·diag(1/s).
    Vec3 normal(const Vec3& n) const { return (rotation * n.cwiseQuotient(scale)).normalized(); }
    bool uniform_scale() const { return scale.x() == scale.y() && scale.y() == scale.z(); }
};

/// Applies `t` to every position and normal in place.
void transform_mesh(TriangleMesh& mesh, const Transform& t);

/// Axis-aligned box of the given edge lengths centred at the origin (flat faces).
TriangleMesh make_box(const Vec3& size);
/// Rectangle in the xy plane centred at the origin, normal +z.
TriangleMesh make_plane(double size_x, double size_y);
/// Disk in the xy plane centred at the origin, normal +z.
TriangleMesh make_disk(double radius, int segments);
/// Cylinder along z from −height/2 to +height/2 with smooth sides and flat caps.
TriangleMesh make_cylinder(double radius, double height, int segments, bool caps);

/// Reads OBJ, PLY, glTF (anything assimp reads) into one mesh in file units, vertex order kept
/// (so per-vertex data files line up). Throws tirpol::Error naming the file for a missing,
/// unreadable or empty mesh.
TriangleMesh load_mesh_file(const std::filesystem::path& path);

}  // namespace tirpol::simulation
