// Regions of the twin's images from the truth render's geometry channels.

#include "regions.h"

#include <algorithm>
#include <cmath>

#include "tirpol/core/error.h"

namespace tirpol::twin {

std::size_t object_index(const simulation::Scene& scene, const std::string& name) {
    std::string names;
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        if (scene.objects[i].name == name) return i;
        names += (i ? ", " : "") + scene.objects[i].name;
    }
    fail("{}: no object named '{}' (objects: {})", scene.file.string(), name, names);
}

namespace {

bool all_object(const Image& render, std::size_t object, int x0, int y0, int x1, int y1) {
    const auto& id = render.channel("object_id");
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x)
            if (id[render.index(x, y)] != static_cast<float>(object)) return false;
    return true;
}

}  // namespace

std::optional<calibration::PixelRect> object_rect(const Image& render, std::size_t object) {
    const auto& id = render.channel("object_id");
    int x0 = render.width(), y0 = render.height(), x1 = -1, y1 = -1;
    for (int y = 0; y < render.height(); ++y)
        for (int x = 0; x < render.width(); ++x)
            if (id[render.index(x, y)] == static_cast<float>(object)) {
                x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x + 1),
                y1 = std::max(y1, y + 1);
            }
    if (x1 < 0) return std::nullopt;
    // Shrink the box one pixel per side until it holds only the object; the panels are convex
    // quadrilaterals, so this converges on a rectangle well inside the silhouette.
    while (x1 - x0 > 2 && y1 - y0 > 2 && !all_object(render, object, x0, y0, x1, y1)) {
        const int before = (x1 - x0) + (y1 - y0);
        if (!all_object(render, object, x0, y0, x0 + 1, y1)) ++x0;
        if (!all_object(render, object, x1 - 1, y0, x1, y1)) --x1;
        if (!all_object(render, object, x0, y0, x1, y0 + 1)) ++y0;
        if (!all_object(render, object, x0, y1 - 1, x1, y1)) --y1;
        // A non-convex silhouette (the ground around the rack) can have all four sides inside the
        // object and a hole within: shrink every side, or the loop would never end.
        if ((x1 - x0) + (y1 - y0) == before) ++x0, --x1, ++y0, --y1;
    }
    // Margin: pixels next to the edge mix in the neighbour through the render's anti-aliasing.
    x0 += 1, y0 += 1, x1 -= 1, y1 -= 1;
    if (x1 - x0 < 2 || y1 - y0 < 2 || !all_object(render, object, x0, y0, x1, y1))
        return std::nullopt;
    return calibration::PixelRect{x0, y0, x1 - x0, y1 - y0};
}

double plane_of_emission_angle(const Image& render, const simulation::PinholeCamera& camera,
                               const calibration::PixelRect& rect) {
    const auto mean = [&](const char* channel) {
        return calibration::region_mean(render, channel, rect, "twin").mean;
    };
    const Vec3 normal = Vec3(mean("normal_x"), mean("normal_y"), mean("normal_z")).normalized();
    // The p direction is the normal's component across the ray through the rectangle's centre; its
    // angle is measured in the image Stokes frame of that ray: 0° = camera right projected on the
    // wavefront, 90° toward the image top (ARCHITECTURE.md). Off the optical axis this differs from
    // projecting the normal on the sensor plane by several degrees.
    const Vec3 d =
        camera.ray_direction(rect.x + 0.5 * rect.width, rect.y + 0.5 * rect.height).normalized();
    const auto across = [&d](const Vec3& v) { return Vec3(v - v.dot(d) * d).normalized(); };
    const Vec3 reference = across(camera.world_from_camera().col(0));
    Vec3 up = d.cross(reference);
    if (up.dot(-camera.world_from_camera().col(1)) < 0.0) up = -up;
    const Vec3 p = across(normal);
    return std::atan2(p.dot(up), p.dot(reference));
}

PlaneOfEmissionEmissivity in_plane_of_emission(const calibration::EmissivityResult& e, double psi) {
    // A frame with its 0° axis along s (ψ − 90°): S1' = −(S1 cos 2ψ + S2 sin 2ψ).
    const double c2 = std::cos(2.0 * psi), s2 = std::sin(2.0 * psi);
    return {e.eps_s0, e.eps_s0_std, -(e.eps_s1 * c2 + e.eps_s2 * s2),
            std::hypot(e.eps_s1_std * c2, e.eps_s2_std * s2)};
}

}  // namespace tirpol::twin
