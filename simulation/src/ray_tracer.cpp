#include "tirpol/simulation/ray_tracer.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "tirpol/core/error.h"
#include "tirpol/core/log.h"

namespace tirpol::simulation {

struct RayTracer::EmbreeHandles {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::size_t buffer_bytes = 0;
};

namespace {
void embree_error(void*, RTCError code, const char* message) {
    // Logged here; the failing call is also checked by its caller through rtcGetDeviceError.
    spdlog::error("Embree error {}: {}", static_cast<int>(code), message ? message : "");
}
}  // namespace

RayTracer::RayTracer() : m_embree(std::make_unique<EmbreeHandles>()) {
    m_embree->device = rtcNewDevice(nullptr);
    if (!m_embree->device)
        fail("Embree: cannot create a device (error {})",
             static_cast<int>(rtcGetDeviceError(nullptr)));
    rtcSetDeviceErrorFunction(m_embree->device, embree_error, nullptr);
    m_embree->scene = rtcNewScene(m_embree->device);
    rtcSetSceneBuildQuality(m_embree->scene, RTC_BUILD_QUALITY_HIGH);
}

RayTracer::~RayTracer() {
    if (m_embree->scene) rtcReleaseScene(m_embree->scene);
    if (m_embree->device) rtcReleaseDevice(m_embree->device);
}

std::uint32_t RayTracer::add_mesh(TriangleMesh mesh) {
    if (m_committed) fail("RayTracer: add_mesh after commit");
    RTCGeometry geom = rtcNewGeometry(m_embree->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), mesh.positions.size()));
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
        for (int c = 0; c < 3; ++c)
            vertices[3 * i + static_cast<std::size_t>(c)] =
                static_cast<float>(mesh.positions[i][c]);
    auto* indices = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(unsigned), mesh.triangles.size()));
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
        for (std::size_t c = 0; c < 3; ++c) indices[3 * i + c] = mesh.triangles[i][c];
    rtcCommitGeometry(geom);
    const auto id = static_cast<std::uint32_t>(m_objects.size());
    rtcAttachGeometryByID(m_embree->scene, geom, id);
    rtcReleaseGeometry(geom);
    m_embree->buffer_bytes +=
        mesh.positions.size() * 3 * sizeof(float) + mesh.triangles.size() * 3 * sizeof(unsigned);
    // The same arithmetic as a per-hit evaluation would use, so hits are unchanged to the bit.
    std::vector<Vec3> face_normals;
    face_normals.reserve(mesh.triangles.size());
    for (const auto& tri : mesh.triangles) {
        const Vec3& p0 = mesh.positions[tri[0]];
        face_normals.push_back(
            (mesh.positions[tri[1]] - p0).cross(mesh.positions[tri[2]] - p0).normalized());
    }
    m_objects.push_back(Object{std::move(mesh), std::move(face_normals), false, Vec3::Zero(), 0.0});
    return id;
}

std::uint32_t RayTracer::add_sphere(const Vec3& center, double radius) {
    if (m_committed) fail("RayTracer: add_sphere after commit");
    if (!(radius > 0.0)) fail("RayTracer: sphere radius must be positive, got {}", radius);
    RTCGeometry geom = rtcNewGeometry(m_embree->device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    auto* p = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                          RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
    p[0] = static_cast<float>(center.x());
    p[1] = static_cast<float>(center.y());
    p[2] = static_cast<float>(center.z());
    p[3] = static_cast<float>(radius);
    rtcCommitGeometry(geom);
    const auto id = static_cast<std::uint32_t>(m_objects.size());
    rtcAttachGeometryByID(m_embree->scene, geom, id);
    rtcReleaseGeometry(geom);
    m_embree->buffer_bytes += 4 * sizeof(float);
    m_objects.push_back(Object{TriangleMesh{}, {}, true, center, radius});
    return id;
}

void RayTracer::commit() {
    rtcCommitScene(m_embree->scene);
    const RTCError err = rtcGetDeviceError(m_embree->device);
    if (err != RTC_ERROR_NONE)
        fail("Embree: building the BVH failed (error {})", static_cast<int>(err));
    m_committed = true;
}

namespace {
RTCRay make_ray(const Vec3& o, const Vec3& d, double t_min, double t_max) {
    RTCRay r{};
    r.org_x = static_cast<float>(o.x());
    r.org_y = static_cast<float>(o.y());
    r.org_z = static_cast<float>(o.z());
    r.dir_x = static_cast<float>(d.x());
    r.dir_y = static_cast<float>(d.y());
    r.dir_z = static_cast<float>(d.z());
    r.tnear = static_cast<float>(t_min);
    r.tfar = static_cast<float>(std::min(t_max, 1e30));
    r.mask = 0xFFFFFFFFu;
    r.flags = 0;
    r.time = 0.0f;
    return r;
}

/// Embree's closest hit along the ray (geomID RTC_INVALID_GEOMETRY_ID: none).
RTCRayHit closest_hit(RTCScene scene, const Vec3& origin, const Vec3& direction, double t_min,
                      double t_max) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray = make_ray(origin, direction, t_min, t_max);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &context, &rh);
    return rh;
}
}  // namespace

std::optional<SurfaceHit> RayTracer::intersect(const Vec3& origin, const Vec3& direction,
                                               double t_min, double t_max) const {
    const RTCRayHit rh = closest_hit(m_embree->scene, origin, direction, t_min, t_max);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;

    SurfaceHit hit;
    hit.object = rh.hit.geomID;
    hit.primitive = rh.hit.primID;
    hit.distance = rh.ray.tfar;
    const Object& obj = m_objects[hit.object];
    if (obj.is_sphere) {
        // Analytic normal and position refined onto the sphere: smooth up to the limb.
        const Vec3 n = (origin + hit.distance * direction - obj.center).normalized();
        hit.position = obj.center + obj.radius * n;
        hit.geometric_normal = hit.shading_normal = n;
        hit.uv = Eigen::Vector2d(0.5 + std::atan2(n.y(), n.x()) / (2.0 * kPi),
                                 std::acos(std::clamp(n.z(), -1.0, 1.0)) / kPi);
        return hit;
    }
    hit.b1 = rh.hit.u;
    hit.b2 = rh.hit.v;
    const auto& tri = obj.mesh.triangles[hit.primitive];
    const double b0 = 1.0 - hit.b1 - hit.b2;
    const Vec3& p0 = obj.mesh.positions[tri[0]];
    const Vec3& p1 = obj.mesh.positions[tri[1]];
    const Vec3& p2 = obj.mesh.positions[tri[2]];
    hit.geometric_normal = obj.face_normals[hit.primitive];
    hit.position = b0 * p0 + hit.b1 * p1 + hit.b2 * p2;
    Vec3 ns = b0 * obj.mesh.normals[tri[0]] + hit.b1 * obj.mesh.normals[tri[1]] +
              hit.b2 * obj.mesh.normals[tri[2]];
    hit.shading_normal = ns.squaredNorm() > 1e-20 ? ns.normalized() : hit.geometric_normal;
    hit.uv =
        b0 * obj.mesh.uvs[tri[0]] + hit.b1 * obj.mesh.uvs[tri[1]] + hit.b2 * obj.mesh.uvs[tri[2]];
    return hit;
}

double RayTracer::nearest_distance(const Vec3& origin, const Vec3& direction, double t_min,
                                   double t_max) const {
    const RTCRayHit rh = closest_hit(m_embree->scene, origin, direction, t_min, t_max);
    return rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? std::numeric_limits<double>::infinity()
                                                    : rh.ray.tfar;
}

bool RayTracer::occluded(const Vec3& origin, const Vec3& direction, double t_min,
                         double t_max) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay r = make_ray(origin, direction, t_min, t_max);
    rtcOccluded1(m_embree->scene, &context, &r);
    return r.tfar < 0.0f;  // Embree sets tfar = −inf on a hit
}

std::size_t RayTracer::memory_bytes() const {
    std::size_t bytes = m_embree->buffer_bytes;
    for (const auto& o : m_objects)
        bytes += o.mesh.positions.size() * (2 * sizeof(Vec3) + sizeof(Eigen::Vector2d)) +
                 o.mesh.triangles.size() * (sizeof(o.mesh.triangles[0]) + sizeof(Vec3));
    return bytes;
}

}  // namespace tirpol::simulation
