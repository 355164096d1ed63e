#include "tirpol/core/quadrature.h"

#include <cmath>

#include "tirpol/core/error.h"
#include "tirpol/core/geometry.h"

namespace tirpol {

QuadratureRule gauss_legendre(int n) {
    if (n < 1) fail("Gauss–Legendre rule with {} nodes; expected at least 1", n);
    QuadratureRule rule;
    const auto count = static_cast<std::size_t>(n);
    rule.nodes.resize(count);
    rule.weights.resize(count);
    for (int i = 0; i < n; ++i) {
        double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
        double derivative = 1.0;
        for (int iteration = 0; iteration < 100; ++iteration) {
            double p0 = 1.0, p1 = x;
            for (int j = 2; j <= n; ++j) {
                const double p2 = ((2.0 * j - 1.0) * x * p1 - (j - 1.0) * p0) / j;
                p0 = p1;
                p1 = p2;
            }
            // P_n'(x) from P_n and P_{n-1}.
            derivative = n * (x * p1 - p0) / (x * x - 1.0);
            const double step = p1 / derivative;
            x -= step;
            if (std::abs(step) < 1e-15) break;
        }
        const auto k = static_cast<std::size_t>(i);
        rule.nodes[k] = 0.5 * (1.0 - x);
        rule.weights[k] =
            1.0 / ((1.0 - x * x) * derivative * derivative);  // 2/((1−x²)P'²), halved for [0, 1]
    }
    return rule;
}

QuadratureRule composite_rule(const QuadratureRule& unit_rule, int panels, double a, double b) {
    QuadratureRule rule;
    const double width = (b - a) / panels;
    for (int p = 0; p < panels; ++p)
        for (std::size_t i = 0; i < unit_rule.nodes.size(); ++i) {
            rule.nodes.push_back(a + (p + unit_rule.nodes[i]) * width);
            rule.weights.push_back(unit_rule.weights[i] * width);
        }
    return rule;
}

QuadratureRule composite_rule(const QuadratureRule& unit_rule, const std::vector<double>& edges) {
    QuadratureRule rule;
    for (std::size_t e = 0; e + 1 < edges.size(); ++e) {
        const double lo = edges[e], width = edges[e + 1] - edges[e];
        if (!(width > 0.0)) continue;
        for (std::size_t i = 0; i < unit_rule.nodes.size(); ++i) {
            rule.nodes.push_back(lo + unit_rule.nodes[i] * width);
            rule.weights.push_back(unit_rule.weights[i] * width);
        }
    }
    return rule;
}

}  // namespace tirpol
