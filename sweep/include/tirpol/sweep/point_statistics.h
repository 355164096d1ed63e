#pragma once
/// \file point_statistics.h
/// Region statistics of one rendered sweep point: mean S0, S1, S2 (camera frame, band radiance
/// W/(m²·sr)), mean per-pixel DoLP and mean temperature over each region, with the Monte-Carlo
/// standard error of each mean, and contrasts mean(a) − mean(b) between regions.
///
/// Errors: the renderer's S*_var channels are the variance of each pixel's mean (renderer.h);
/// pixels are independent samples, so the error of a region mean is √(Σ var_i)/n. A pixel's DoLP
/// variance is propagated to first order from S0, S1, S2. The error of a contrast is √(σ_a² + σ_b²)
/// (disjoint regions are independent). NaN errors with one sample per pixel; NaN means for an empty
/// region.

#include <string>
#include <vector>

#include "tirpol/core/image.h"
#include "tirpol/sweep/sweep_file.h"

namespace tirpol::sweep {

struct Estimate {
    double mean = 0.0;
    double error = 0.0;  ///< Monte-Carlo standard error of the mean
};

/// The quantities of one region or contrast, in the order of kQuantityNames.
struct QuantityEstimates {
    Estimate s0, s1, s2, dolp, temperature_k;
};
inline constexpr const char* kQuantityNames[] = {"S0", "S1", "S2", "DoLP", "temperature_k"};
const Estimate& quantity(const QuantityEstimates& q, std::size_t index);

struct RegionStatistics {
    std::string name;
    std::size_t pixel_count = 0;
    QuantityEstimates values;
};

struct ContrastStatistics {
    std::string name;
    QuantityEstimates values;  ///< mean(a) − mean(b)
};

struct PointStatistics {
    std::vector<RegionStatistics> regions;
    std::vector<ContrastStatistics> contrasts;
};

/// Statistics of a rendered image (renderer.h channels) over the sweep's regions; `objects` are the
/// scene's object names in object_id order. Throws tirpol::Error if a region's polygon leaves the
/// image.
PointStatistics point_statistics(const Image& image, const std::vector<std::string>& objects,
                                 const SweepSpec& spec);

/// The pixels of a region: 1 inside, 0 outside (row-major, the image's size).
std::vector<std::uint8_t> region_pixels(const Image& image, const std::vector<std::string>& objects,
                                        const RegionSpec& region);

}  // namespace tirpol::sweep
