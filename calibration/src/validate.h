#pragma once
// Input checks shared by the calibration algorithms: done once before the per-pixel loops, so the
// loops themselves never throw (STYLE.md).

#include <cmath>
#include <span>
#include <string>

#include "tirpol/core/error.h"

namespace tirpol::calibration::detail {

/// Throws unless `plane` has `expected` values, all finite; `what` names the source in the message.
inline void check_plane(std::span<const float> plane, std::size_t expected, const std::string& what,
                        int width, int height) {
    if (plane.size() != expected)
        fail("{}: image has {} pixels, expected {} ({}×{}, the size of the other images)", what,
             plane.size(), expected, width, height);
    std::size_t bad = 0, first = 0;
    for (std::size_t i = 0; i < plane.size(); ++i)
        if (!std::isfinite(plane[i]) && bad++ == 0) first = i;
    if (bad > 0)
        fail("{}: {} pixel(s) are NaN or infinite (first at x={}, y={}); expected finite values",
             what, bad, first % static_cast<std::size_t>(width),
             first / static_cast<std::size_t>(width));
}

/// check_plane for a σ image, which must also hold no negative value (a standard deviation).
inline void check_std_plane(std::span<const float> plane, std::size_t expected,
                            const std::string& what, int width, int height) {
    check_plane(plane, expected, what, width, height);
    std::size_t bad = 0, first = 0;
    for (std::size_t i = 0; i < plane.size(); ++i)
        if (plane[i] < 0.0f && bad++ == 0) first = i;
    if (bad > 0)
        fail("{}: {} pixel(s) are negative (first at x={}, y={}: {}); a standard deviation is ≥ 0",
             what, bad, first % static_cast<std::size_t>(width),
             first / static_cast<std::size_t>(width), plane[first]);
}

}  // namespace tirpol::calibration::detail
