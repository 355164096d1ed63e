#pragma once
// Private sampling helpers of the pBRDF models.

#include <algorithm>
#include <cmath>

#include "tirpol/core/geometry.h"

namespace tirpol::materials::detail {

/// Cosine-weighted direction on the upper hemisphere (Malley's method; pdf = cosθ/π).
inline Vec3 sample_cosine_hemisphere(double u1, double u2) {
    const double r = std::sqrt(std::clamp(u1, 0.0, 1.0));
    const double phi = 2.0 * kPi * u2;
    return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u1))};
}

inline double cosine_hemisphere_pdf(const Vec3& w) { return w.z() > 0.0 ? w.z() / kPi : 0.0; }

}  // namespace tirpol::materials::detail
