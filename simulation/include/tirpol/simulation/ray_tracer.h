#pragma once
/// \file ray_tracer.h
/// The scene's geometry in an Embree 3 BVH: triangle meshes and analytic spheres. Thread-safe
/// queries (Embree's rtcIntersect1/rtcOccluded1 on a committed scene).
///
/// Triangle meshes of scene objects: procedural primitives and files read through assimp.

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
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

/// Reads OBJ, PLY, glTF (anything assimp reads) into one mesh in file units and the file's own
/// axes, vertex order kept (so per-vertex data files line up). Throws tirpol::Error naming the
/// file for a missing, unreadable or empty mesh.
TriangleMesh load_mesh_file(const std::filesystem::path& path);

/// Name assimp gives OBJ faces before any `usemtl`. A `usemtl` name keeps its name
/// even when no .mtl file defines it; a glTF primitive without `material` gets an
/// empty name.
inline constexpr std::string_view kNoFileMaterial = "DefaultMaterial";

/// A mesh file's triangles and the material each one uses, by the name the file gives it: OBJ
/// `usemtl` names (defined in the .mtl files of its `mtllib`), glTF materials' `name`.
struct MeshFile {
    TriangleMesh mesh;
    std::vector<std::string> material_names;       ///< distinct names, in order of first use
    std::vector<std::uint32_t> triangle_material;  ///< per triangle: index into material_names
};

/// As load_mesh_file, with each triangle's material name: a glTF primitive's `material` index picks
/// a material whose `name` is used; an unnamed one (or a primitive without `material`) gives an
/// empty name (assimp renumbers glTF materials, so the index itself cannot name it).
MeshFile read_mesh_file(const std::filesystem::path& path);

/// The axis of a mesh file that points up; tirpol's world is z-up (east, north, up).
enum class UpAxis { y, z };

/// "y" or "z" (the scene file's `up_axis`); nullopt for anything else.
std::optional<UpAxis> up_axis_from_name(std::string_view name);
/// The up axis a file's format defines: y for glTF 2.0 (.gltf, .glb), whose specification (Khronos
/// glTF 2.0.1, section 3.4 "Coordinate System and Units") makes +Y up, +Z forward (the front of an
/// asset faces +Z) and −X right; z for the rest: OBJ and PLY define no axes, and their files are
/// taken as written.
UpAxis default_up_axis(const std::filesystem::path& path);
/// Rotation from a file's axes to tirpol's z-up world: identity for z; for y, +90° about x,
/// (x, y, z) ↦ (x, −z, y), which undoes Blender's z-up → glTF y-up export, so a glTF's up (+Y)
/// becomes +z and its front (+Z) faces −y (south, toward a camera placed at negative y).
Mat3 z_up_rotation(UpAxis axis);

/// A ray–surface intersection in world coordinates.
struct SurfaceHit {
    double distance = 0.0;  ///< along the (unit) ray direction, m
    Vec3 position;
    Vec3 geometric_normal;  ///< unit, outward as built (not flipped toward the ray)
    Vec3 shading_normal;    ///< unit, interpolated vertex normal (analytic for spheres), outward
    Eigen::Vector2d uv = Eigen::Vector2d::Zero();
    std::uint32_t object = 0;     ///< index of the object in the order it was added
    std::uint32_t primitive = 0;  ///< triangle index (0 for spheres)
    double b1 = 0.0, b2 = 0.0;    ///< barycentric weights of the triangle's 2nd and 3rd vertex
};

class RayTracer {
public:
    RayTracer();
    ~RayTracer();
    RayTracer(const RayTracer&) = delete;
    RayTracer& operator=(const RayTracer&) = delete;

    /// Adds a triangle mesh (world coordinates); returns its object index.
    std::uint32_t add_mesh(TriangleMesh mesh);
    /// Adds an analytic sphere; returns its object index.
    std::uint32_t add_sphere(const Vec3& center, double radius);
    /// Builds the BVH; call once after adding everything and before any query.
    void commit();

    /// Nearest hit along origin + t·direction for t in (t_min, t_max).
    std::optional<SurfaceHit> intersect(const Vec3& origin, const Vec3& direction,
                                        double t_min = 0.0, double t_max = 1e30) const;
    /// Distance to the nearest hit (+inf on a miss) from rtcIntersect1 alone, without the hit
    /// record `intersect` builds: the reference cost of a ray for benchmarks.
    double nearest_distance(const Vec3& origin, const Vec3& direction, double t_min = 0.0,
                            double t_max = 1e30) const;
    /// True if anything lies along the segment (t_min, t_max).
    bool occluded(const Vec3& origin, const Vec3& direction, double t_min, double t_max) const;

    std::size_t object_count() const { return m_objects.size(); }
    /// The triangle mesh of an object (empty for a sphere).
    const TriangleMesh& mesh(std::uint32_t object) const { return m_objects[object].mesh; }
    /// Rough bytes held by the geometry (our copies plus Embree's vertex/index buffers).
    std::size_t memory_bytes() const;

private:
    struct Object {
        TriangleMesh mesh;
        /// Unit geometric normal of each triangle, computed once instead of at every hit.
        std::vector<Vec3> face_normals;
        bool is_sphere = false;
        Vec3 center = Vec3::Zero();
        double radius = 0.0;
    };
    struct EmbreeHandles;
    std::unique_ptr<EmbreeHandles> m_embree;
    std::vector<Object> m_objects;
    bool m_committed = false;
};

}  // namespace tirpol::simulation
