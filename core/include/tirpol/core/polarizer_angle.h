#pragma once
/// \file polarizer_angle.h
/// Nominal polarizer (analyzer) angles as keys: the one rule by which a session record, an analyzer
/// position, a wire-grid calibration entry and an EXR channel name refer to "the same angle". Two
/// nominal angles are the same when they agree to the hundredth of a degree (plans write 0, 45.0,
/// 22.5; a float round trip through a file changes them far less). Angles are not wrapped: 0° and
/// 180° are different positions of the mount.

#include <cmath>
#include <string>

namespace tirpol {

/// The nominal angle in hundredths of a degree, rounded: equal keys ⇔ the same angle.
inline long polarizer_angle_key(double angle_deg) { return std::lround(angle_deg * 100.0); }

/// Whether two nominal angles name the same polarizer position (equal keys).
inline bool same_polarizer_angle(double a_deg, double b_deg) {
    return polarizer_angle_key(a_deg) == polarizer_angle_key(b_deg);
}

/// The angle of a key, degrees.
inline double polarizer_angle_deg(long key) { return static_cast<double>(key) / 100.0; }

/// The angle as it appears in channel names: shortest form of its key's angle with '.' → 'p'
/// ("0", "45", "22p5", "-10"), so 45 and 45.0 give the same name.
std::string polarizer_angle_tag(double angle_deg);

/// `angle_deg` wrapped to [0, 360).
inline double wrap_degrees(double angle_deg) {
    double a = std::fmod(angle_deg, 360.0);
    if (a < 0.0) a += 360.0;
    return a >= 360.0 ? 0.0 : a;
}

/// Signed smallest difference a − b in degrees, in [−180, 180) (how far a stage is from a request).
inline double angle_difference_deg(double a_deg, double b_deg) {
    return wrap_degrees(a_deg - b_deg + 180.0) - 180.0;
}

}  // namespace tirpol
