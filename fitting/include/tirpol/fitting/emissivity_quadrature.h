#pragma once
/// \file emissivity_quadrature.h
/// Fixed-node quadrature of the polarized directional emissivity of the micro-facet model
/// (emissivity.h, paper eq 5 as Stokes):
///   ε_S0(θo) = 1 − ∫ M00(wi→wo) cosθi dωi,   ε_S1(θo) = −∫ M10(wi→wo) cosθi dωi,
/// with wo at polar angle θo and azimuth 0. The nodes depend only on θo (data), never on the model's
/// parameters, so the sum is a smooth function of the parameters that ceres::Jet differentiates
/// exactly (automatic differentiation "through the quadrature"). The materials module's own integrator
/// maps the BRDF's importance sampler onto the unit square, whose nodes move with σ; this one is the
/// Jet-friendly counterpart and is verified against it (tests/fitting/emissivity_quadrature_test.cpp).
///
/// Nodes: composite Gauss–Legendre in θi ∈ [0, π/2] and φi ∈ [0, π] (M00 and M10 are even in φi by the
/// mirror symmetry of an isotropic surface, so the φi ∈ [π, 2π] half is the same and the weights are
/// doubled). Panel edges are graded towards the specular direction (θi = θo, φi = π), where the
/// micro-facet lobe concentrates, θo ± {0.04, 0.12, 0.3, 0.6} rad and π − {0.1, 0.3, 0.7, 1.5} rad, and
/// repeated scaled by 2·cosθo beyond 60°, where the lobe narrows in wi-space like cosθo.

#include <utility>
#include <vector>

#include "tirpol/materials/shell_target_math.h"

namespace tirpol::fitting {

struct QuadratureOptions {
    int order = 4;  ///< Gauss–Legendre nodes per panel (1..16); 4 keeps |Δε| < 1e-3 for σ ≥ 0.1 (test)
};

/// The quadrature nodes of one emission angle, with the parameter-independent geometry cached.
class EmissivityQuadrature {
public:
    EmissivityQuadrature(double emission_angle_rad, const QuadratureOptions& options = {});

    /// (ε_S0, ε_S1) of the micro-facet model with parameters `p` (τ, Ω in radians) at this angle.
    template <typename T>
    std::pair<T, T> emissivity(const materials::ShellTargetParameters<T>& p) const {
        T reflected_s0(0.0), reflected_s1(0.0);
        for (const Node& node : m_nodes) {
            const materials::Mueller4<T> m = materials::shell_target_mueller(p, node.geometry);
            reflected_s0 += m[0][0] * node.weight;
            reflected_s1 += m[1][0] * node.weight;
        }
        return {T(1.0) - reflected_s0, -reflected_s1};
    }

    double emission_angle_rad() const { return m_emission_angle_rad; }
    std::size_t node_count() const { return m_nodes.size(); }

private:
    struct Node {
        materials::MicrofacetGeometry geometry;
        double weight;  ///< GL weight × cosθi sinθi × 2 (both φ halves)
    };
    double m_emission_angle_rad;
    std::vector<Node> m_nodes;
};

}  // namespace tirpol::fitting
