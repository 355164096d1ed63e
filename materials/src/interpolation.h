#pragma once
// Private helpers shared by the tables of this module.

#include <algorithm>
#include <vector>

namespace tirpol::materials::detail {

/// Linear interpolation of y(x) on increasing x, clamped to the end values outside.
inline double interpolate_linear(const std::vector<double>& x, const std::vector<double>& y,
                                 double at) {
    if (at <= x.front()) return y.front();
    if (at >= x.back()) return y.back();
    const auto it = std::upper_bound(x.begin(), x.end(), at);
    const auto i = static_cast<std::size_t>(it - x.begin());
    const double t = (at - x[i - 1]) / (x[i] - x[i - 1]);
    return y[i - 1] + t * (y[i] - y[i - 1]);
}

}  // namespace tirpol::materials::detail
