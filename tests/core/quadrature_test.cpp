// Gauss–Legendre quadrature (core/quadrature.h): the published nodes and weights, exactness for
// polynomials of degree ≤ 2n − 1, and composite rules.

#include "tirpol/core/quadrature.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "tirpol/core/error.h"
#include "tirpol/core/geometry.h"

namespace tirpol {
namespace {

double integrate(const QuadratureRule& rule, double (*f)(double)) {
    double sum = 0.0;
    for (std::size_t i = 0; i < rule.nodes.size(); ++i) sum += rule.weights[i] * f(rule.nodes[i]);
    return sum;
}

// Abramowitz & Stegun, Handbook of Mathematical Functions, Table 25.4 (on [−1, 1]): n = 2 has nodes
// ±0.577350269189626 with weight 1; n = 3 has 0 (weight 8/9) and ±0.774596669241483 (weight 5/9).
// Mapped to [0, 1]: x → (1 − x)/2, weights halved.
TEST(Quadrature, GaussLegendreMatchesTabulatedNodesAndWeights) {
    const QuadratureRule two = gauss_legendre(2);
    ASSERT_EQ(two.nodes.size(), 2u);
    EXPECT_NEAR(two.nodes[0], 0.5 * (1.0 - 0.577350269189626), 1e-15);
    EXPECT_NEAR(two.nodes[1], 0.5 * (1.0 + 0.577350269189626), 1e-15);
    EXPECT_NEAR(two.weights[0], 0.5, 1e-15);
    const QuadratureRule three = gauss_legendre(3);
    ASSERT_EQ(three.nodes.size(), 3u);
    EXPECT_NEAR(three.nodes[0], 0.5 * (1.0 - 0.774596669241483), 1e-15);
    EXPECT_NEAR(three.nodes[1], 0.5, 1e-15);
    EXPECT_NEAR(three.weights[0], 0.5 * 5.0 / 9.0, 1e-14);
    EXPECT_NEAR(three.weights[1], 0.5 * 8.0 / 9.0, 1e-14);
}

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

// The Gauss–Legendre remainder on [a, b] (Abramowitz & Stegun 25.4.30):
//   ∫f − Σ w f(x) = (b − a)^(2n+1) (n!)⁴ / ((2n + 1) ((2n)!)³) · f^(2n)(ξ).
double remainder_factor(int n, double width) {
    return std::pow(width, 2 * n + 1) * std::pow(factorial(n), 4) /
           ((2 * n + 1) * std::pow(factorial(2 * n), 3));
}

// An n-point rule integrates x^k exactly for k ≤ 2n − 1 (∫₀¹ x^k dx = 1/(k + 1)); for k = 2n the
// remainder is the formula above with f^(2n) = (2n)!.
TEST(Quadrature, GaussLegendreIsExactUpToDegreeTwoNMinusOne) {
    for (int n = 1; n <= 16; ++n) {
        const QuadratureRule rule = gauss_legendre(n);
        for (int k = 0; k <= 2 * n; ++k) {
            double sum = 0.0;
            for (std::size_t i = 0; i < rule.nodes.size(); ++i)
                sum += rule.weights[i] * std::pow(rule.nodes[i], k);
            if (k <= 2 * n - 1) {
                EXPECT_NEAR(sum, 1.0 / (k + 1), 1e-14) << "n = " << n << ", k = " << k;
            } else if (n <= 6) {  // beyond, the remainder (< 1e-8) drowns in rounding of the powers
                const double remainder = remainder_factor(n, 1.0) * factorial(2 * n);
                EXPECT_NEAR(1.0 / (k + 1) - sum, remainder, 1e-6 * remainder) << "n = " << n;
            }
        }
    }
    EXPECT_THROW(gauss_legendre(0), Error);
}

// ∫₀^π sin = 2, on equal panels and on uneven edges (with a repeated edge, an empty panel).
TEST(Quadrature, CompositeRulesIntegrateOverTheirPanels) {
    const QuadratureRule unit = gauss_legendre(4);
    const auto sine = [](double x) { return std::sin(x); };
    const QuadratureRule equal = composite_rule(unit, 6, 0.0, kPi);
    EXPECT_EQ(equal.nodes.size(), 24u);
    EXPECT_NEAR(integrate(equal, sine), 2.0, 1e-10);
    EXPECT_NEAR(std::accumulate(equal.weights.begin(), equal.weights.end(), 0.0), kPi, 1e-14);
    const QuadratureRule uneven =
        composite_rule(unit, std::vector<double>{0.0, 0.1, 0.1, 1.0, 3.0, kPi});
    EXPECT_EQ(uneven.nodes.size(), 16u);
    // |sin⁽⁸⁾| ≤ 1: the remainder is bounded by the sum of the panels' factors.
    double bound = 0.0;
    for (double width : {0.1, 0.9, 2.0, kPi - 3.0}) bound += remainder_factor(4, width);
    EXPECT_NEAR(integrate(uneven, sine), 2.0, bound);
    EXPECT_GT(std::abs(integrate(uneven, sine) - 2.0), 1e-3 * bound);  // the coarse panel is felt
}

}  // namespace
}  // namespace tirpol
