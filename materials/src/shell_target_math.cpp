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
    // cos α and sin α as in core's frame_rotation_angle (atan2 arguments of unit vectors), so
    // cos 2α = c² − s², sin 2α = 2cs without trigonometry.
    const Vec3 n = Vec3::UnitZ();
    const auto double_angle = [](const StokesFrame& from, const StokesFrame& to, double& c2, double& s2) {
        const double c = to.reference.dot(from.reference), s = to.reference.dot(from.second_axis());
        const double norm2 = c * c + s * s;
        c2 = (c * c - s * s) / norm2;
        s2 = 2.0 * c * s / norm2;
    };
    double_angle(surface_frame(-wi, n), surface_frame(-wi, h), g.c2i, g.s2i);
    double_angle(surface_frame(wo, h), surface_frame(wo, n), g.c2o, g.s2o);
    return g;
}

}  // namespace tirpol::materials
