#pragma once
/// \file quadrature.h
/// Gauss–Legendre quadrature: the one rule the integrators share (materials' hemispherical
/// emissivity, fitting's fixed-node emissivity quadrature).

#include <vector>

namespace tirpol {

struct QuadratureRule {
    std::vector<double> nodes;
    std::vector<double> weights;  ///< sum to the length of the interval
};

/// n-point Gauss–Legendre rule on [0, 1], by Newton's method on the Legendre polynomial P_n from
/// the Tricomi initial guesses (Press et al., Numerical Recipes 3rd ed., §4.6.1); exact for
/// polynomials of degree ≤ 2n − 1. n ≥ 1.
QuadratureRule gauss_legendre(int n);

/// `unit_rule` (a rule on [0, 1]) on each of `panels` equal panels of [a, b].
QuadratureRule composite_rule(const QuadratureRule& unit_rule, int panels, double a, double b);

/// `unit_rule` on each interval [edges[i], edges[i+1]] (edges increasing; empty intervals skipped).
QuadratureRule composite_rule(const QuadratureRule& unit_rule, const std::vector<double>& edges);

}  // namespace tirpol
