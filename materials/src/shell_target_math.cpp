#include <algorithm>
#include <cmath>

#include "tirpol/core/stokes_frame.h"
#include "tirpol/materials/microfacet.h"

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
    // For one beam direction k, the s axes of the frames about normals a and b are a × k and b × k
    // (both ⟂ k), and the angle α from the first to the second (core frame_rotation_angle) has
    // cos α ∝ (b × k)·(a × k) and sin α ∝ (b × k)·(k × (a × k)) = (b × k)·a (k a unit vector: k ×
    // (a × k) = a − (a·k)k) with the same factor |a × k||b × k|, so cos 2α = (c² − s²)/(c² + s²)
    // and sin 2α = 2cs/(c² + s²) need neither normalisation nor trigonometry. Where a × k = 0 (a
    // beam along the normal) the s axis is core's fallback convention (stokes_frame.h), so those
    // rare exact cases take the frames themselves.
    const Vec3 n = Vec3::UnitZ();
    const auto double_angle = [](const Vec3& k, const Vec3& from_normal, const Vec3& to_normal,
                                 double& c2, double& s2) {
        const Vec3 from_s = from_normal.cross(k), to_s = to_normal.cross(k);
        double c = to_s.dot(from_s), s = to_s.dot(from_normal);
        if (from_s.squaredNorm() == 0.0 || to_s.squaredNorm() == 0.0) {
            const StokesFrame from = surface_frame(k, from_normal),
                              to = surface_frame(k, to_normal);
            c = to.reference.dot(from.reference);
            s = to.reference.dot(from.second_axis());
        }
        const double inv_norm2 = 1.0 / (c * c + s * s);
        c2 = (c * c - s * s) * inv_norm2;
        s2 = 2.0 * c * s * inv_norm2;
    };
    double_angle(-wi, n, h, g.c2i, g.s2i);
    double_angle(wo, h, n, g.c2o, g.s2o);
    return g;
}

}  // namespace tirpol::materials
