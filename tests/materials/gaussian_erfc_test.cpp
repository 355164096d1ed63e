// erfc_given_gaussian (Cody's rational approximations on a given e^(−x²)) against published values
// and glibc's erfc.

#include "gaussian_erfc.h"

#include <gtest/gtest.h>

#include <cmath>

namespace tirpol::materials::detail {
namespace {

double erfc_of(double x) { return erfc_given_gaussian(x, std::exp(-x * x)); }

// Reference values computed with mpmath at 40 digits (they agree with Abramowitz & Stegun table
// 7.1 to its 10 digits): one in each of Cody's three regions.
TEST(GaussianErfc, MatchesReferenceValues) {
    EXPECT_NEAR(erfc_of(0.0), 1.0, 0.0);
    EXPECT_NEAR(erfc_of(0.3) / 0.67137324054087258, 1.0, 1e-15);
    EXPECT_NEAR(erfc_of(1.0) / 0.15729920705028513066, 1.0, 1e-15);
    EXPECT_NEAR(erfc_of(2.0) / 0.0046777349810472658379, 1.0, 2e-15);
    EXPECT_NEAR(erfc_of(5.0) / 1.5374597944280348502e-12, 1.0, 5e-15);
}

// Over the range where Smith's Λ is evaluated (a < 6) and beyond, the only error is the rounding
// of x² in e^(−x²): relative ≤ 1.1e-16·x² plus a few ulps, and continuous across the region borders
// 0.46875 and 4 to that accuracy.
TEST(GaussianErfc, AgreesWithLibm) {
    for (double x = 0.0; x <= 10.0; x += 1.0 / 1024.0 + 1e-9) {
        const double expected = std::erfc(x);
        EXPECT_NEAR(erfc_of(x) / expected, 1.0, 2.2e-16 * (8.0 + x * x)) << "x = " << x;
    }
    // Across a border the two sides may each be off by that bound, no more.
    for (const double border : {0.46875, 4.0}) {
        const double bound = 2.0 * 2.2e-16 * (8.0 + border * border);
        const double below = erfc_of(std::nextafter(border, 0.0)), at = erfc_of(border),
                     above = erfc_of(std::nextafter(border, 10.0));
        EXPECT_NEAR(below / at, 1.0, bound) << border;
        EXPECT_NEAR(above / at, 1.0, bound) << border;
    }
}

}  // namespace
}  // namespace tirpol::materials::detail
