#pragma once
/// \file ray_tracer.h
/// The scene's geometry in an Embree 3 BVH: triangle meshes and analytic spheres. Thread-safe
/// queries (Embree's rtcIntersect1/rtcOccluded1 on a committed scene).

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "tirpol/simulation/mesh.h"

namespace tirpol::simulation {

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
