#include "microgrid_newton_row.h"

#include <algorithm>

#include "stokes_row.h"

namespace tirpol::calibration::detail {

namespace {

/// One analyzer's estimate at p from the N directions s in which it sits at q = p + s: near =
/// other(q), own_far = own(p + 2s), other_far = other(p + 3s). Smooth: the mean of other(q) +
/// ⅜(own(p) − own(p + 2s)) (the quadratic Newton polynomial); edge: the one-sided other(q) +
/// ½(own(p) − own(p + 2s)) weighted by 1/(ε + g_s)², g_s the variation along s; blended by the
/// ratio of the largest to the smallest variation (≤ 3 smooth, ≥ 8 edge). The weights are scaled
/// by (ε + g_min)² (they are only used normalised) so that none overflows.
template <int N>
inline float newton_estimate(float own, const float (&near)[N], const float (&own_far)[N],
                             const float (&other_far)[N], float epsilon) {
    constexpr float kSmoothRatio = 3.0f, kEdgeRatio = 8.0f;
    float difference[N], gradient[N];
    for (int i = 0; i < N; ++i) {
        difference[i] = own - own_far[i];
        gradient[i] = std::abs(difference[i]) + std::abs(near[i] - other_far[i]);
    }
    float g_min = gradient[0], g_max = gradient[0];
    for (int i = 1; i < N; ++i) {
        g_min = std::min(g_min, gradient[i]);
        g_max = std::max(g_max, gradient[i]);
    }
    const float floor = g_min + epsilon;
    const float edge = std::clamp(
        ((g_max + epsilon) / floor - kSmoothRatio) / (kEdgeRatio - kSmoothRatio), 0.0f, 1.0f);
    float smooth = 0.0f, weighted = 0.0f, weight_sum = 0.0f;
    for (int i = 0; i < N; ++i) {
        smooth += near[i] + 0.375f * difference[i];
        const float h = floor / (gradient[i] + epsilon);
        weighted += h * h * (near[i] + 0.5f * difference[i]);
        weight_sum += h * h;
    }
    smooth *= 1.0f / static_cast<float>(N);
    return (1.0f - edge) * smooth + edge * (weighted / weight_sum);
}

/// The row loop, also built for AVX2 and picked at load time (as the bilinear single pass).
TIRPOL_MICROGRID_CLONES
void newton_row_loop(const float* __restrict u3, const float* __restrict u2,
                     const float* __restrict u1, const float* __restrict c,
                     const float* __restrict d1, const float* __restrict d2,
                     const float* __restrict d3, std::ptrdiff_t width, float epsilon,
                     float* __restrict horizontal, float* __restrict vertical,
                     float* __restrict diagonal) {
    for (std::ptrdiff_t x = 0; x < width; ++x) {
        const float own = c[x];
        const float h_near[2] = {c[x - 1], c[x + 1]}, h_own[2] = {c[x - 2], c[x + 2]},
                    h_other[2] = {c[x - 3], c[x + 3]};
        horizontal[x] = newton_estimate<2>(own, h_near, h_own, h_other, epsilon);
        const float v_near[2] = {u1[x], d1[x]}, v_own[2] = {u2[x], d2[x]},
                    v_other[2] = {u3[x], d3[x]};
        vertical[x] = newton_estimate<2>(own, v_near, v_own, v_other, epsilon);
        const float d_near[4] = {u1[x - 1], u1[x + 1], d1[x - 1], d1[x + 1]},
                    d_own[4] = {u2[x - 2], u2[x + 2], d2[x - 2], d2[x + 2]},
                    d_other[4] = {u3[x - 3], u3[x + 3], d3[x - 3], d3[x + 3]};
        diagonal[x] = newton_estimate<4>(own, d_near, d_own, d_other, epsilon);
    }
}

}  // namespace

void newton_row(const PaddedMosaic& frame, int y, std::size_t width, float epsilon,
                float* horizontal, float* vertical, float* diagonal) {
    newton_row_loop(frame.row(y, -3), frame.row(y, -2), frame.row(y, -1), frame.row(y, 0),
                    frame.row(y, 1), frame.row(y, 2), frame.row(y, 3),
                    static_cast<std::ptrdiff_t>(width), epsilon, horizontal, vertical, diagonal);
}

}  // namespace tirpol::calibration::detail
