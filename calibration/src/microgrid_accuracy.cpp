#include "microgrid_accuracy.h"

#include <algorithm>
#include <cmath>

#include "tirpol/core/error.h"

namespace tirpol::calibration {

StokesErrors compare_to_truth(const Image& estimate, std::span<const float> s0,
                              std::span<const float> s1, std::span<const float> s2, int width,
                              int height, int border_px, std::span<const unsigned char> mask) {
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    if (s0.size() != n || s1.size() != n || s2.size() != n || (!mask.empty() && mask.size() != n))
        fail("compare_to_truth: truth planes or mask do not hold {}×{} values", width, height);
    int scale = 1;
    if (estimate.width() == width / 2 && estimate.height() == height / 2 && width % 2 == 0 &&
        height % 2 == 0)
        scale = 2;
    else if (estimate.width() != width || estimate.height() != height)
        fail("compare_to_truth: the estimate is {}×{}; expected {}×{} or half of it (super-pixel)",
             estimate.width(), estimate.height(), width, height);
    const auto& e0 = estimate.channel("S0");
    const auto& e1 = estimate.channel("S1");
    const auto& e2 = estimate.channel("S2");
    const auto& edolp = estimate.channel("DoLP");
    StokesErrors errors;
    double sum0 = 0.0, sum1 = 0.0, sum2 = 0.0, sum_dolp = 0.0;
    for (int y = border_px; y < height - border_px; ++y)
        for (int x = border_px; x < width - border_px; ++x) {
            const std::size_t t = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                                  static_cast<std::size_t>(x);
            if (!mask.empty() && mask[t] == 0) continue;
            const std::size_t e = estimate.index(x / scale, y / scale);
            const double true_dolp =
                std::hypot(static_cast<double>(s1[t]), static_cast<double>(s2[t])) / s0[t];
            const double d0 = e0[e] - s0[t], d1 = e1[e] - s1[t], d2 = e2[e] - s2[t],
                         dd = edolp[e] - true_dolp;
            sum0 += d0 * d0;
            sum1 += d1 * d1;
            sum2 += d2 * d2;
            sum_dolp += dd * dd;
            errors.dolp_max = std::max(errors.dolp_max, std::abs(dd));
            ++errors.pixels;
        }
    if (errors.pixels == 0)
        fail("compare_to_truth: no pixel left to compare (border {} px, mask)", border_px);
    const double count = static_cast<double>(errors.pixels);
    errors.s0_rms = std::sqrt(sum0 / count);
    errors.s1_rms = std::sqrt(sum1 / count);
    errors.s2_rms = std::sqrt(sum2 / count);
    errors.dolp_rms = std::sqrt(sum_dolp / count);
    return errors;
}

}  // namespace tirpol::calibration
