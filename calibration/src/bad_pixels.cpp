#include <algorithm>
#include <cmath>
#include <limits>

#include "tirpol/calibration/radiometric.h"

namespace tirpol::calibration {

namespace {
double median_of(std::vector<double>& v) {
    const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    double m = *mid;
    if (v.size() % 2 == 0) m = 0.5 * (m + *std::max_element(v.begin(), mid));
    return m;
}
}  // namespace

RobustStats robust_stats(const std::vector<float>& values) {
    std::vector<double> v;
    v.reserve(values.size());
    for (float x : values)
        if (std::isfinite(x)) v.push_back(x);
    if (v.empty())
        return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
    const double med = median_of(v);
    for (double& x : v) x = std::abs(x - med);
    // 1.4826·MAD estimates σ of a normal distribution (Rousseeuw & Croux 1993).
    return {med, 1.4826 * median_of(v)};
}

void replace_bad_pixels(std::vector<float>& plane, const std::vector<float>& bad_mask, int width,
                        int height) {
    if (std::all_of(bad_mask.begin(), bad_mask.end(), [](float b) { return b == 0.0f; })) return;
    const std::vector<float> source = plane;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                                  static_cast<std::size_t>(x);
            if (bad_mask[i] == 0.0f) continue;
            float value = std::numeric_limits<float>::quiet_NaN();
            for (int r = 1; r <= 3 && std::isnan(value); ++r) {
                double sum = 0.0;
                int n = 0;
                for (int yy = std::max(0, y - r); yy <= std::min(height - 1, y + r); ++yy)
                    for (int xx = std::max(0, x - r); xx <= std::min(width - 1, x + r); ++xx) {
                        const std::size_t j =
                            static_cast<std::size_t>(yy) * static_cast<std::size_t>(width) +
                            static_cast<std::size_t>(xx);
                        if (bad_mask[j] != 0.0f || !std::isfinite(source[j])) continue;
                        sum += source[j];
                        ++n;
                    }
                if (n > 0) value = static_cast<float>(sum / n);
            }
            plane[i] = value;
        }
}

}  // namespace tirpol::calibration
