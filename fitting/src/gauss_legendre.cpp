#include "gauss_legendre.h"

#include <cmath>

#include "tirpol/core/geometry.h"

namespace tirpol::fitting::detail {

QuadratureRule gauss_legendre(int n, double a, double b) {
    QuadratureRule rule;
    const auto count = static_cast<std::size_t>(n);
    rule.nodes.resize(count);
    rule.weights.resize(count);
    const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
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
        rule.nodes[k] = mid - half * x;
        rule.weights[k] = 2.0 * half / ((1.0 - x * x) * derivative * derivative);
    }
    return rule;
}

QuadratureRule composite_gauss_legendre(int n, const std::vector<double>& edges) {
    QuadratureRule out;
    for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
        if (!(edges[i + 1] > edges[i])) continue;
        const QuadratureRule panel = gauss_legendre(n, edges[i], edges[i + 1]);
        out.nodes.insert(out.nodes.end(), panel.nodes.begin(), panel.nodes.end());
        out.weights.insert(out.weights.end(), panel.weights.begin(), panel.weights.end());
    }
    return out;
}

}  // namespace tirpol::fitting::detail
