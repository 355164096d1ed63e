#pragma once
// The per-pixel tail of a Stokes reduction on whole rows of float planes: realizability projection,
// DoLP and AoP, written as branch-free loops the compiler vectorises (the single-pass microgrid
// reductions use it; reduce_stokes does the same per pixel in double with its σ bookkeeping).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>

// The row loops are also compiled for AVX2 and chosen at load time (GCC function multi-versioning
// through an ifunc): the build itself targets plain x86-64. Elsewhere, one version.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define TIRPOL_MICROGRID_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define TIRPOL_MICROGRID_CLONES
#endif

namespace tirpol::calibration::detail {

/// AoP = ½·atan2(s2, s1) in degrees, [0°, 180°), to float rounding (a polynomial atan after
/// Cephes' atanf, relative error < 2·10⁻⁷, so that the loops that call it vectorise); NaN if s1 or
/// s2 is.
inline float aop_deg(float s1, float s2) {
    constexpr float kPi = std::numbers::pi_v<float>;
    const float ax = std::fabs(s1), ay = std::fabs(s2);
    const bool steep = ay > ax;
    const float num = steep ? ax : ay, den = steep ? ay : ax;
    // Every quotient is computed, then selected: a division under a condition keeps the loop
    // from vectorising (it could trap). den = 0 means num = 0, so the floor gives t = 0.
    float t = num / std::max(den, std::numeric_limits<float>::min());  // [0, 1]
    // Cephes atanf: above tan(π/8), atan t = π/4 + atan((t − 1)/(t + 1)), |argument| ≤ tan(π/8).
    const bool upper = t > 0.414213562373095f;
    const float base = upper ? 0.25f * kPi : 0.0f;
    const float shifted = (t - 1.0f) / (t + 1.0f);
    t = upper ? shifted : t;
    const float z = t * t;
    const float poly = ((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z -
                       3.33329491539e-1f;
    float r = (poly * z * t + t) + base;
    r = steep ? 0.5f * kPi - r : r;
    r = s1 < 0.0f ? kPi - r : r;
    r = s2 < 0.0f ? -r : r;
    float aop = r * (90.0f / kPi);
    aop = aop < 0.0f ? aop + 180.0f : aop;
    return (s1 != s1) | (s2 != s2) ? std::numeric_limits<float>::quiet_NaN() : aop;
}

/// For `count` pixels: with `project_to_realizable`, (s1, s2) of a vector with √(s1² + s2²) > s0 ≥
/// 0 is scaled onto the cone, as reduce_stokes does; then dolp = √(s1² + s2²)/s0 (NaN unless s0 >
/// 0) and aop = aop_deg(s1, s2). Returns how many vectors were unrealizable (counted with or
/// without the projection).
std::size_t finish_stokes_row(float* s0, float* s1, float* s2, float* dolp, float* aop,
                              std::size_t count, bool project_to_realizable);

}  // namespace tirpol::calibration::detail
