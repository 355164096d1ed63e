#include "stokes_row.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

namespace tirpol::calibration::detail {

namespace {
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
}  // namespace

namespace {

// __restrict: the five rows never overlap (distinct channels); without it the compiler needs more
// run-time overlap checks than it emits. The counter is 32-bit like the float lanes (a 64-bit one
// kept the loop scalar); a row is far shorter.
template <bool kProject>
TIRPOL_MICROGRID_CLONES std::uint32_t finish(const float* __restrict s0, float* __restrict s1,
                                             float* __restrict s2, float* __restrict dolp,
                                             float* __restrict aop, std::size_t count) {
    std::uint32_t unrealizable = 0;
    for (std::size_t i = 0; i < count; ++i) {
        const float p0 = s0[i];
        float p1 = s1[i], p2 = s2[i];
        float pl = std::sqrt(p1 * p1 + p2 * p2);
        const bool outside = (pl > p0) & (p0 >= 0.0f);
        unrealizable += outside ? 1u : 0u;
        if constexpr (kProject) {
            const float ratio = p0 / pl;  // selected only where pl > p0 ≥ 0, so pl > 0
            const float scale = outside ? ratio : 1.0f;
            p1 *= scale;
            p2 *= scale;
            pl = outside ? p0 : pl;
            s1[i] = p1;
            s2[i] = p2;
        }
        const float degree = pl / p0;
        dolp[i] = p0 > 0.0f ? degree : kNaN;
        aop[i] = aop_deg(p1, p2);
    }
    return unrealizable;
}

}  // namespace

std::size_t finish_stokes_row(float* s0, float* s1, float* s2, float* dolp, float* aop,
                              std::size_t count, bool project_to_realizable) {
    return project_to_realizable ? finish<true>(s0, s1, s2, dolp, aop, count)
                                 : finish<false>(s0, s1, s2, dolp, aop, count);
}

}  // namespace tirpol::calibration::detail
