#pragma once
/// \file region_mean.h
/// The mean of an image quantity over a pixel rectangle and the standard error of that mean: the
/// one ROI statistic of emissivity extraction (the region means of paper eq 17) and of the digital
/// twin.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>

#include "tirpol/core/error.h"
#include "tirpol/core/image.h"

namespace tirpol::calibration {

/// A pixel rectangle [x, y, width, height] (origin top-left).
struct PixelRect {
    int x = 0, y = 0, width = 0, height = 0;
};

struct RegionMean {
    double mean = 0.0;
    /// Of `mean`: sample standard deviation (n − 1) over √n, pixels treated as independent; 0 for n
    /// = 1.
    double standard_error = 0.0;
    std::size_t n = 0;  ///< finite pixels used
};

/// Mean and standard error of value(x, y) over the pixels of `rect` where it is finite (NaN and ±∞
/// skipped). `rect` must lie inside the image(s) `value` reads. Throws tirpol::Error naming `what`
/// and `quantity` when no value is finite.
template <class Value>
RegionMean region_mean_of(const PixelRect& rect, const std::string& what,
                          const std::string& quantity, Value&& value) {
    double sum = 0.0, sum2 = 0.0;
    std::size_t n = 0;
    for (int y = rect.y; y < rect.y + rect.height; ++y)
        for (int x = rect.x; x < rect.x + rect.width; ++x) {
            const double v = value(x, y);
            if (!std::isfinite(v)) continue;
            sum += v;
            sum2 += v * v;
            ++n;
        }
    if (n == 0)
        fail("{}: no finite {} pixel in the rectangle [{}, {}, {}, {}]", what, quantity, rect.x,
             rect.y, rect.width, rect.height);
    const double count = static_cast<double>(n);
    const double mean = sum / count;
    const double variance =
        n > 1 ? std::max(0.0, (sum2 - count * mean * mean) / (count - 1.0)) : 0.0;
    return {mean, std::sqrt(variance / count), n};
}

/// region_mean_of() of channel `channel` of `image`; throws tirpol::Error naming `what` when `rect`
/// is not inside the image.
RegionMean region_mean(const Image& image, const std::string& channel, const PixelRect& rect,
                       const std::string& what);

}  // namespace tirpol::calibration
