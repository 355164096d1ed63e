#pragma once
/// \file geometry.h
/// Vector types of the world frame: right-handed, x east, y north, z up (ARCHITECTURE.md).

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace tirpol {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

inline constexpr double kPi = 3.14159265358979323846;

/// Global "up" of the world frame.
inline Vec3 world_up() { return Vec3::UnitZ(); }

inline constexpr double deg_to_rad(double deg) { return deg * (kPi / 180.0); }
inline constexpr double rad_to_deg(double rad) { return rad * (180.0 / kPi); }

}  // namespace tirpol
