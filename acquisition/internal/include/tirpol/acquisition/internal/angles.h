#pragma once
/// \file angles.h
/// Angle helpers for rotation stages (degrees).

#include <cmath>

namespace tirpol::acquisition {

/// `angle_deg` wrapped to [0, 360).
inline double wrap_degrees(double angle_deg) {
    double a = std::fmod(angle_deg, 360.0);
    if (a < 0.0) a += 360.0;
    return a >= 360.0 ? 0.0 : a;
}

/// Signed smallest difference a − b in degrees, in [−180, 180).
inline double angle_difference_deg(double a_deg, double b_deg) {
    return wrap_degrees(a_deg - b_deg + 180.0) - 180.0;
}

}  // namespace tirpol::acquisition
