#include <algorithm>
#include <cmath>

#include "tirpol/core/error.h"
#include "tirpol/core/quadrature.h"
#include "tirpol/fitting/microfacet_fit.h"

namespace tirpol::fitting {

namespace {
constexpr double kHalfPi = 0.5 * kPi;

// Sorted, de-duplicated panel edges inside [lo, hi], always including lo and hi.
std::vector<double> panel_edges(double lo, double hi, std::vector<double> inner) {
    inner.push_back(lo);
    inner.push_back(hi);
    std::vector<double> edges;
    for (double e : inner)
        if (e >= lo && e <= hi) edges.push_back(e);
    std::sort(edges.begin(), edges.end());
    edges.erase(
        std::unique(edges.begin(), edges.end(), [](double a, double b) { return b - a < 1e-6; }),
        edges.end());
    return edges;
}
}  // namespace

EmissivityQuadrature::EmissivityQuadrature(double emission_angle_rad,
                                           const QuadratureOptions& options)
    : m_emission_angle_rad(emission_angle_rad) {
    if (!(emission_angle_rad >= 0.0 && emission_angle_rad <= kHalfPi))
        fail("emission angle {} rad is outside [0, π/2]", emission_angle_rad);
    if (options.order < 1 || options.order > 16)
        fail("quadrature order {} is outside 1..16", options.order);

    const double t = emission_angle_rad;
    // Edges graded towards the specular direction. Near grazing the lobe narrows in wi-space like
    // cosθo (wi + wo nearly cancels sideways, so a small turn of wi swings the facet normal a lot):
    // the same grading is repeated scaled by 2·cosθo there.
    const double shrink = std::min(1.0, 2.0 * std::cos(t));
    std::vector<double> theta_inner = {t};
    std::vector<double> phi_inner;
    for (double scale : {1.0, shrink}) {
        for (double d : {0.04, 0.12, 0.3, 0.6}) {
            theta_inner.push_back(t - d * scale);
            theta_inner.push_back(t + d * scale);
        }
        for (double d : {0.1, 0.3, 0.7, 1.5}) phi_inner.push_back(kPi - d * scale);
    }
    const QuadratureRule unit_rule = gauss_legendre(options.order);
    const QuadratureRule theta = composite_rule(unit_rule, panel_edges(0.0, kHalfPi, theta_inner));
    const QuadratureRule phi = composite_rule(unit_rule, panel_edges(0.0, kPi, phi_inner));

    // wo at the clamped grazing limit, as materials::hemispherical_reflected_stokes does.
    const double cos_o = std::max(std::cos(t), materials::kMinCosine);
    const Vec3 wo(std::sqrt(std::max(0.0, 1.0 - cos_o * cos_o)), 0.0, cos_o);
    m_nodes.reserve(theta.nodes.size() * phi.nodes.size());
    for (std::size_t i = 0; i < theta.nodes.size(); ++i) {
        const double st = std::sin(theta.nodes[i]), ct = std::cos(theta.nodes[i]);
        Row row{0.0, m_nodes.size(), m_nodes.size()};
        for (std::size_t j = 0; j < phi.nodes.size(); ++j) {
            const Vec3 wi(st * std::cos(phi.nodes[j]), st * std::sin(phi.nodes[j]), ct);
            const materials::MicrofacetGeometry g = materials::microfacet_geometry(wi, wo);
            if (!g.valid) continue;
            // ×2: the φi ∈ [π, 2π] half mirrors this one.
            const double weight = 2.0 * theta.weights[i] * phi.weights[j] * g.cos_i * st;
            const double c4 = g.cos_n * g.cos_n * g.cos_n * g.cos_n;
            m_nodes.push_back({g.tan2_n, g.theta_n, g.cos_beta, g.beta, g.c2o,
                               weight / (4.0 * g.cos_i * g.cos_o * c4)});
            m_diffuse_sum += weight;
            m_volume_sum += weight * 2.0 / (g.cos_i + g.cos_o);
            m_cot_o = g.cot_o;
            row.cot_i = g.cot_i;
        }
        row.end = m_nodes.size();
        if (row.end > row.begin) m_rows.push_back(row);
    }
}

}  // namespace tirpol::fitting
