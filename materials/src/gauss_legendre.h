#pragma once
// Gauss–Legendre nodes and weights on [0, 1] (private helper of the integrators).

#include <cmath>
#include <vector>

#include "tirpol/core/geometry.h"

namespace tirpol::materials::detail {

struct QuadratureRule {
    std::vector<double> nodes;    ///< in (0, 1)
    std::vector<double> weights;  ///< sum to 1
};

/// n-point Gauss–Legendre rule on [0, 1], by Newton's method on P_n (Press et al., Numerical Recipes
/// 3rd ed., §4.6.1); exact for polynomials of degree ≤ 2n − 1.
inline QuadratureRule gauss_legendre(int n) {
    QuadratureRule rule;
    rule.nodes.resize(static_cast<std::size_t>(n));
    rule.weights.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
        double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
        double dp = 1.0;
        for (int iter = 0; iter < 100; ++iter) {
            double p0 = 1.0, p1 = x;
            for (int j = 2; j <= n; ++j) {
                const double p2 = ((2.0 * j - 1.0) * x * p1 - (j - 1.0) * p0) / j;
                p0 = p1;
                p1 = p2;
            }
            if (n == 1) p0 = 1.0;
            dp = n * (x * p1 - p0) / (x * x - 1.0);
            const double dx = p1 / dp;
            x -= dx;
            if (std::abs(dx) < 1e-15) break;
        }
        const auto k = static_cast<std::size_t>(i);
        rule.nodes[k] = 0.5 * (1.0 - x);
        rule.weights[k] = 1.0 / ((1.0 - x * x) * dp * dp);  // 2/((1−x²)P'²) scaled by ½ for [0, 1]
    }
    return rule;
}

/// Composite rule: `panels` equal panels of [a, b], each with the n-point rule.
inline QuadratureRule composite(const QuadratureRule& base, int panels, double a, double b) {
    QuadratureRule rule;
    const double width = (b - a) / panels;
    for (int p = 0; p < panels; ++p)
        for (std::size_t i = 0; i < base.nodes.size(); ++i) {
            rule.nodes.push_back(a + (p + base.nodes[i]) * width);
            rule.weights.push_back(base.weights[i] * width);
        }
    return rule;
}

}  // namespace tirpol::materials::detail
