#include "pooled_variance.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace tirpol::report {

namespace {

bool same_label(float a, float b) { return a == b || (std::isnan(a) && std::isnan(b)); }

}  // namespace

double satterthwaite_pooled_dof(double sum, double sum_of_squares, int count,
                                double dof_per_pixel) {
    const double most = dof_per_pixel * count;
    if (!(sum_of_squares > 0.0)) return most;
    const double dof = (dof_per_pixel + 2.0) * sum * sum / sum_of_squares - 2.0;
    return std::clamp(dof, dof_per_pixel, most);
}

PooledVariance pool_variance(const std::vector<float>& variance,
                             const std::vector<const std::vector<float>*>& labels, int width,
                             int height, int radius_px, double dof_per_pixel) {
    const auto index = [width](int x, int y) {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
               static_cast<std::size_t>(x);
    };
    PooledVariance out{std::vector<float>(variance.size(), std::numeric_limits<float>::quiet_NaN()),
                       std::vector<float>(variance.size(), 0.0f)};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t centre = index(x, y);
            double sum = 0.0, sum_of_squares = 0.0;
            int count = 0;
            for (int v = std::max(0, y - radius_px); v <= std::min(height - 1, y + radius_px); ++v)
                for (int u = std::max(0, x - radius_px); u <= std::min(width - 1, x + radius_px);
                     ++u) {
                    const std::size_t j = index(u, v);
                    if (!std::isfinite(variance[j])) continue;
                    const bool same = std::all_of(labels.begin(), labels.end(), [&](auto* plane) {
                        return same_label((*plane)[j], (*plane)[centre]);
                    });
                    if (!same) continue;
                    sum += variance[j];
                    sum_of_squares += static_cast<double>(variance[j]) * variance[j];
                    ++count;
                }
            if (count == 0) continue;
            out.variance[centre] = static_cast<float>(sum / count);
            out.dof[centre] = static_cast<float>(
                satterthwaite_pooled_dof(sum, sum_of_squares, count, dof_per_pixel));
        }
    return out;
}

}  // namespace tirpol::report
