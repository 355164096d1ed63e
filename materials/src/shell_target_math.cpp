#include <algorithm>
#include <cmath>

#include "gaussian_erfc.h"
#include "tirpol/core/stokes.h"
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

double smith_lambda_from_gaussian(double sigma, double cot_theta) {
    const double a = cot_theta / (std::sqrt(2.0) * sigma);
    const double e = std::exp(-a * a);
    return (e / (a * std::sqrt(kPi)) - detail::erfc_given_gaussian(a, e)) * 0.5;
}

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
    // The macro-surface normal is z, so its s axis n × k = (−k.y, k.x, 0) and (b × k)·n = (b × k).z
    // are written out: GCC keeps the general forms' products by 0 (they could be NaN), and the
    // dropped terms only ever added a zero, so the results are the same doubles.
    const auto double_angle = [](double c, double s, bool degenerate, const Vec3& k,
                                 const Vec3& from_normal, const Vec3& to_normal, double& c2,
                                 double& s2) {
        if (degenerate) {
            const StokesFrame from = surface_frame(k, from_normal),
                              to = surface_frame(k, to_normal);
            c = to.reference.dot(from.reference);
            s = to.reference.dot(from.second_axis());
        }
        const double inv_norm2 = 1.0 / (c * c + s * s);
        c2 = (c * c - s * s) * inv_norm2;
        s2 = 2.0 * c * s * inv_norm2;
    };
    const Vec3 n = Vec3::UnitZ();
    {  // incident: k = −wi, from the macro frame (n × k = (wi.y, −wi.x, 0)) to the facet's
        const Vec3 k = -wi;
        const double macro_x = wi.y(), macro_y = -wi.x();
        const Vec3 facet_s = h.cross(k);
        const double c = facet_s.x() * macro_x + facet_s.y() * macro_y, s = facet_s.z();
        const bool degenerate =
            macro_x * macro_x + macro_y * macro_y == 0.0 || facet_s.squaredNorm() == 0.0;
        double_angle(c, s, degenerate, k, n, h, g.c2i, g.s2i);
    }
    {  // exitant: k = wo, from the facet's frame to the macro frame (n × k = (−wo.y, wo.x, 0))
        const Vec3 facet_s = h.cross(wo);
        const double macro_x = -wo.y(), macro_y = wo.x();
        const double c = macro_x * facet_s.x() + macro_y * facet_s.y(),
                     s = macro_x * h.x() + macro_y * h.y();
        const bool degenerate =
            facet_s.squaredNorm() == 0.0 || macro_x * macro_x + macro_y * macro_y == 0.0;
        double_angle(c, s, degenerate, wo, h, n, g.c2o, g.s2o);
    }
    return g;
}

}  // namespace tirpol::materials
