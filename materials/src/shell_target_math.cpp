#include "tirpol/materials/shell_target_math.h"

#include <algorithm>
#include <cmath>

#include "tirpol/core/stokes_frame.h"

namespace tirpol::materials {

namespace {
// Cotangent capped so that Λ's exponentials underflow to exactly 0 (with finite Jet derivatives)
// at normal incidence instead of producing inf·0.
constexpr double kMaxCotangent = 1e8;

double cotangent(double cos_theta) {
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    return sin_theta * kMaxCotangent <= cos_theta ? kMaxCotangent : cos_theta / sin_theta;
}
}  // namespace

MicrofacetGeometry microfacet_geometry(const Vec3& wi, const Vec3& wo) {
    MicrofacetGeometry g;
    if (!(wi.z() > 0.0) || !(wo.z() > 0.0)) return g;
    g.valid = true;
    g.cos_i = std::max(wi.z(), kMinCosine);
    g.cos_o = std::max(wo.z(), kMinCosine);
    const Vec3 h = (wi + wo).normalized();
    g.cos_n = std::clamp(h.z(), kMinCosine, 1.0);
    g.tan2_n = (1.0 - g.cos_n * g.cos_n) / (g.cos_n * g.cos_n);
    g.theta_n = std::acos(g.cos_n);
    g.cos_beta = std::clamp(h.dot(wi), 0.0, 1.0);
    g.beta = std::acos(g.cos_beta);
    g.cot_i = cotangent(wi.z());
    g.cot_o = cotangent(wo.z());

    // Incident beam (travelling along −wi): macro s/p frame → facet s/p frame; exitant beam: back.
    const Vec3 n = Vec3::UnitZ();
    const MuellerMatrix rot_in =
        frame_rotation(frame_rotation_angle(surface_frame(-wi, n), surface_frame(-wi, h)));
    const MuellerMatrix rot_out = frame_rotation(frame_rotation_angle(surface_frame(wo, h), surface_frame(wo, n)));
    g.c2i = rot_in(1, 1);
    g.s2i = rot_in(1, 2);
    g.c2o = rot_out(1, 1);
    g.s2o = rot_out(1, 2);
    return g;
}

}  // namespace tirpol::materials
