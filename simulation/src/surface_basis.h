#pragma once
// Orthonormal tangent basis around a normal (Duff et al., "Building an orthonormal basis,
// revisited", JCGT 6(1), 2017): continuous except on one half-plane, no branches on a threshold.

#include <cmath>

#include "tirpol/core/geometry.h"

namespace tirpol::simulation::detail {

struct SurfaceBasis {
    Vec3 t, b, n;

    explicit SurfaceBasis(const Vec3& normal) : n(normal) {
        const double sign = std::copysign(1.0, n.z());
        const double a = -1.0 / (sign + n.z());
        const double c = n.x() * n.y() * a;
        t = Vec3(1.0 + sign * n.x() * n.x() * a, sign * c, -sign * n.x());
        b = Vec3(c, sign + n.y() * n.y() * a, -n.y());
    }
    Vec3 to_local(const Vec3& v) const { return {v.dot(t), v.dot(b), v.dot(n)}; }
    Vec3 to_world(const Vec3& v) const { return v.x() * t + v.y() * b + v.z() * n; }
};

}  // namespace tirpol::simulation::detail
