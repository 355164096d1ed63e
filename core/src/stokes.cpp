#include "tirpol/core/stokes.h"

#include <cmath>
#include <limits>

#include "tirpol/core/geometry.h"

namespace tirpol {

StokesVector linearly_polarized(double s0, double degree, double aop) {
    return {s0, s0 * degree * std::cos(2.0 * aop), s0 * degree * std::sin(2.0 * aop), 0.0};
}

// A NaN component (a dead or unmeasured pixel) gives NaN, never 0: 0 would read as "unpolarized".
double dolp(const StokesVector& s) {
    if (std::isnan(s[0]) || std::isnan(s[1]) || std::isnan(s[2]))
        return std::numeric_limits<double>::quiet_NaN();
    return s[0] > 0.0 ? std::hypot(s[1], s[2]) / s[0] : 0.0;
}

double dop(const StokesVector& s) {
    if (s.hasNaN()) return std::numeric_limits<double>::quiet_NaN();
    return s[0] > 0.0 ? s.tail<3>().norm() / s[0] : 0.0;
}

double aop_rad(const StokesVector& s) { return 0.5 * std::atan2(s[2], s[1]); }

double aop_deg_0_180(const StokesVector& s) {
    double deg = rad_to_deg(aop_rad(s));
    if (deg < 0.0) deg += 180.0;
    return deg >= 180.0 ? deg - 180.0 : deg;
}

bool is_realizable(const StokesVector& s, double rel_tol, double abs_tol) {
    if (!s.allFinite()) return false;
    const double tol = std::max(rel_tol * std::abs(s[0]), abs_tol);
    return s[0] >= -tol && s.tail<3>().norm() <= s[0] + tol;
}

}  // namespace tirpol
