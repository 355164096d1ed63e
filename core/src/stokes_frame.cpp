#include <cmath>

#include "tirpol/core/stokes.h"

namespace tirpol {

StokesFrame frame_from_reference(const Vec3& propagation, const Vec3& hint) {
    const Vec3 k = propagation.normalized();
    Vec3 x = hint - hint.dot(k) * k;
    // Hint (nearly) along the beam: the frame is a convention there; pick a fixed, deterministic
    // axis.
    if (x.squaredNorm() < 1e-20 * std::max(hint.squaredNorm(), 1e-300)) {
        const Vec3 fallback = std::abs(k.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
        x = fallback - fallback.dot(k) * k;
    }
    return {k, x.normalized()};
}

StokesFrame world_frame(const Vec3& propagation, const Vec3& up) {
    return frame_from_reference(propagation, up.cross(propagation.normalized()));
}

StokesFrame surface_frame(const Vec3& propagation, const Vec3& normal) {
    return world_frame(propagation, normal);
}

double frame_rotation_angle(const StokesFrame& from, const StokesFrame& to) {
    return std::atan2(to.reference.dot(from.second_axis()), to.reference.dot(from.reference));
}

StokesVector change_frame(const StokesVector& s, const StokesFrame& from, const StokesFrame& to) {
    return frame_rotation(frame_rotation_angle(from, to)) * s;
}

MuellerMatrix change_frame(const MuellerMatrix& m, const StokesFrame& in_from,
                           const StokesFrame& in_to, const StokesFrame& out_from,
                           const StokesFrame& out_to) {
    // Stokes given in in_to → in_from, apply m, then out_from → out_to.
    return frame_rotation(frame_rotation_angle(out_from, out_to)) * m *
           frame_rotation(frame_rotation_angle(in_to, in_from));
}

double paper_rotation_angle(const Vec3& v, const Vec3& normal, const Vec3& up) {
    const Vec3 vi = v.normalized();
    const Vec3 vp = vi.cross(up.cross(vi));  // eq 7: global up projected (the paper's "P" vector)
    const Vec3 vs = vi.cross(vp);            // eq 8
    const Vec3 n_isp = vi.cross(normal.cross(vi));  // eq 9: the normal projected into the S–P plane
    return std::atan2(n_isp.dot(vs),
                      n_isp.dot(vp));  // eq 10, with atan2 so it is defined everywhere
}

}  // namespace tirpol
