#pragma once
// Private: erfc(x) for x ≥ 0 given e^(−x²), for Smith's Λ, which needs both.
#include <cmath>

namespace tirpol::materials::detail {

/// erfc(x) for x ≥ 0 from W. J. Cody's rational Chebyshev approximations ("Rational Chebyshev
/// approximations for the error function", Math. Comp. 23, 631–637, 1969; the coefficients of his
/// CALERF routine, netlib specfun), whose own error is below 1e-17 relative, given `exp_minus_x2`
/// = e^(−x²), which the caller has computed anyway: glibc's erfc evaluates two more exponentials
/// for x ≥ 1.25. Cody splits the exponential to keep its last bit; here the rounding of x² in the
/// caller's e^(−x²) gives a relative error of about x²·1.1e-16 (4e-15 at x = 6), far below what Λ
/// and the visible-slope normalisation can show, as both only add erfc to 1 or 2 (tested against
/// std::erfc).
inline double erfc_given_gaussian(double x, double exp_minus_x2) {
    static constexpr double a[] = {3.1611237438705656, 113.864154151050156, 377.485237685302021,
                                   3209.37758913846947, 0.185777706184603153};
    static constexpr double b[] = {23.6012909523441209, 244.024637934444173, 1282.61652607737228,
                                   2844.23683343917062};
    static constexpr double c[] = {
        0.564188496988670089, 8.88314979438837594, 66.1191906371416295,
        298.635138197400131,  881.95222124176909,  1712.04761263407058,
        2051.07837782607147,  1230.33935479799725, 2.15311535474403846e-8};
    static constexpr double d[] = {15.7449261107098347, 117.693950891312499, 537.181101862009858,
                                   1621.38957456669019, 3290.79923573345963, 4362.61909014324716,
                                   3439.36767414372164, 1230.33935480374942};
    static constexpr double p[] = {0.305326634961232344,   0.360344899949804439,
                                   0.125781726111229246,   0.0160837851487422766,
                                   6.58749161529837803e-4, 0.0163153871373020978};
    static constexpr double q[] = {2.56852019228982242, 1.87295284992346047, 0.527905102951428412,
                                   0.0605183413124413191, 0.00233520497626869185};
    constexpr double kInvSqrtPi = 0.56418958354775628695;
    if (x <= 0.46875) {  // erfc = 1 − erf, erf(x) = x·A(x²)/B(x²)
        const double y = x * x;
        double num = a[4] * y, den = y;
        for (int i = 0; i < 3; ++i) {
            num = (num + a[i]) * y;
            den = (den + b[i]) * y;
        }
        return 1.0 - x * (num + a[3]) / (den + b[3]);
    }
    if (x <= 4.0) {  // erfc = e^(−x²)·C(x)/D(x)
        double num = c[8] * x, den = x;
        for (int i = 0; i < 7; ++i) {
            num = (num + c[i]) * x;
            den = (den + d[i]) * x;
        }
        return exp_minus_x2 * (num + c[7]) / (den + d[7]);
    }
    // erfc = e^(−x²)/x·(1/√π − x⁻²·P(x⁻²)/Q(x⁻²))
    const double y = 1.0 / (x * x);
    double num = p[5] * y, den = y;
    for (int i = 0; i < 4; ++i) {
        num = (num + p[i]) * y;
        den = (den + q[i]) * y;
    }
    return exp_minus_x2 * (kInvSqrtPi - y * (num + p[4]) / (den + q[4])) / x;
}

}  // namespace tirpol::materials::detail
