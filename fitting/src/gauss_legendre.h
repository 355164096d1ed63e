#pragma once
// Gauss–Legendre nodes and weights (private helper of the fixed-node emissivity quadrature).

#include <vector>

namespace tirpol::fitting::detail {

struct QuadratureRule {
    std::vector<double> nodes;
    std::vector<double> weights;
};

/// n-point Gauss–Legendre rule on [a, b]: Newton's method on the Legendre polynomial P_n from the
/// Tricomi initial guesses (Press et al., Numerical Recipes 3rd ed., §4.6.1); exact for polynomials of
/// degree ≤ 2n − 1.
QuadratureRule gauss_legendre(int n, double a, double b);

/// The n-point rule applied on each interval [edges[i], edges[i+1]] (edges increasing).
QuadratureRule composite_gauss_legendre(int n, const std::vector<double>& edges);

}  // namespace tirpol::fitting::detail
