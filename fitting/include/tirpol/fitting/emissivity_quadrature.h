#pragma once
/// \file emissivity_quadrature.h
/// Fixed-node quadrature of the polarized directional emissivity of the micro-facet model
/// (emissivity.h, paper eq 5 as Stokes):
///   ε_S0(θo) = 1 − ∫ M00(wi→wo) cosθi dωi,   ε_S1(θo) = −∫ M10(wi→wo) cosθi dωi,
/// with wo at polar angle θo and azimuth 0. The nodes depend only on θo (data), never on the
/// model's parameters, so the sum is a smooth function of the parameters that ceres::Jet
/// differentiates exactly (automatic differentiation "through the quadrature"). The materials
/// module's own integrator maps the BRDF's importance sampler onto the unit square, whose nodes
/// move with σ; this one is the Jet-friendly counterpart and is verified against it
/// (tests/fitting/emissivity_quadrature_test.cpp).
///
/// Nodes: composite Gauss–Legendre in θi ∈ [0, π/2] and φi ∈ [0, π] (M00 and M10 are even in φi by
/// the mirror symmetry of an isotropic surface, so the φi ∈ [π, 2π] half is the same and the
/// weights are doubled). Panel edges are graded towards the specular direction (θi = θo, φi = π),
/// where the micro-facet lobe concentrates, θo ± {0.04, 0.12, 0.3, 0.6} rad and π − {0.1, 0.3,
/// 0.7, 1.5} rad, and repeated scaled by 2·cosθo beyond 60°, where the lobe narrows in wi-space
/// like cosθo.

#include <cmath>
#include <utility>
#include <vector>

#include "tirpol/materials/fresnel.h"
#include "tirpol/materials/shell_target_math.h"
#include "tirpol/materials/tiny_complex.h"

namespace tirpol::fitting {

struct QuadratureOptions {
    int order =
        4;  ///< Gauss–Legendre nodes per panel (1..16); 4 keeps |Δε| < 1e-3 for σ ≥ 0.1 (test)
};

/// The quadrature nodes of one emission angle, with the parameter-independent geometry cached.
class EmissivityQuadrature {
public:
    EmissivityQuadrature(double emission_angle_rad, const QuadratureOptions& options = {});

    /// (ε_S0, ε_S1) of the micro-facet model with parameters `p` (τ, Ω in radians) at this angle.
    ///
    /// Column 0 of shell_target_mueller (materials/shell_target_math.h) summed over the nodes with
    /// that header's building blocks (gaussian_slope_falloff, smith_lambda,
    /// beard_maxwell_shadowing_reciprocal, fresnel_reflectances), arranged for speed (this runs
    /// with ceres::Jet in every residual evaluation): e0 is unpolarized, so only M00 = s·(Rs+Rp)/2
    /// + ρ_D + 2ρ_V/(cosθi+cosθo) and M10 = s·(Rs−Rp)/2·cos2αo are needed (the frame rotations only
    /// mix columns 1 and 2, and the Fresnel matrix has m20 = 0), with s = bias·D·G·SO/(4 cosθi
    /// cosθo). ñ², 1/(2σ²), 1/τ, 1/Ω, D's constant 1/(2πσ²) and Smith's Λ(θo) are computed once per
    /// call, Λ(θi) once per θi row; D's 1/cos⁴θN is in the node weight. The diffuse and volume
    /// terms are linear in ρ_D, ρ_V, with node sums precomputed. The test checks this against the
    /// materials module's integrator, which evaluates shell_target_mueller itself.
    template <typename T>
    std::pair<T, T> emissivity(const materials::ShellTargetParameters<T>& p) const {
        const T s2 = p.sigma * p.sigma;
        const T inv_2s2 = T(1.0) / (T(2.0) * s2);
        const T d_norm =
            p.bias / (T(2.0 * kPi) * s2);  // bias / (2πσ²), the constant of D times bias
        const T lambda_o = materials::smith_lambda(p.sigma, m_cot_o);
        const materials::TinyComplex<T> eps{p.n * p.n - p.k * p.k, T(2.0) * p.n * p.k};  // ñ²
        const T inv_tau = T(1.0) / p.tau_rad, inv_omega = T(1.0) / p.omega_rad;

        T specular_s0(0.0), specular_s1(0.0);
        for (const Row& row : m_rows) {
            const T shadow =
                T(1.0) / (T(1.0) + materials::smith_lambda(p.sigma, row.cot_i) + lambda_o);
            T row_s0(0.0), row_s1(0.0);
            for (auto it = m_nodes.begin() + static_cast<std::ptrdiff_t>(row.begin),
                      end = m_nodes.begin() + static_cast<std::ptrdiff_t>(row.end);
                 it != end; ++it) {
                const Node& nd = *it;
                const T d = materials::gaussian_slope_falloff(inv_2s2, nd.tan2_n);
                const T so = materials::beard_maxwell_shadowing_reciprocal(inv_tau, inv_omega,
                                                                           nd.theta_n, nd.beta);
                const materials::FresnelReflectances<T> r =
                    materials::fresnel_reflectances(eps, nd.cos_beta);
                const T w = d * so * T(nd.weight_over_c4);
                row_s0 += w * (r.rs2 + r.rp2);
                row_s1 += w * (r.rs2 - r.rp2) * T(nd.cos_2alpha_o);
            }
            specular_s0 += shadow * row_s0;
            specular_s1 += shadow * row_s1;
        }
        // The ½ of (Rs ± Rp)/2 is folded in here.
        const T reflected_s0 =
            T(0.5) * d_norm * specular_s0 + p.rho_d * T(m_diffuse_sum) + p.rho_v * T(m_volume_sum);
        const T reflected_s1 = T(0.5) * d_norm * specular_s1;
        return {T(1.0) - reflected_s0, -reflected_s1};
    }

    double emission_angle_rad() const { return m_emission_angle_rad; }
    std::size_t node_count() const { return m_nodes.size(); }

private:
    struct Node {
        double tan2_n, theta_n;  ///< facet tilt
        double cos_beta, beta;   ///< incidence on the facet
        double cos_2alpha_o;     ///< facet → macro frame of the exitant beam
        double weight_over_c4;  ///< quadrature weight × cosθi sinθi × 2 / (4 cosθi cosθo cos⁴θN)
    };
    struct Row {
        double cot_i;            ///< cotangent of this row's θi (Smith's Λ)
        std::size_t begin, end;  ///< its nodes in m_nodes
    };
    double m_emission_angle_rad;
    double m_cot_o = 0.0;
    double m_diffuse_sum = 0.0;  ///< Σ weight·cosθi: ∫ cosθi dωi (= π up to quadrature error)
    double m_volume_sum = 0.0;  ///< Σ weight·2/(cosθi + cosθo)
    std::vector<Node> m_nodes;
    std::vector<Row> m_rows;
};

}  // namespace tirpol::fitting
