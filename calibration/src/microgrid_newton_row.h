#pragma once
// The Newton-polynomial demosaicing of microgrid_demosaic.cpp (its comment there: directional
// estimates in the polarization-difference domain, blended between the symmetric stencil and the
// edge-weighted one-sided ones), one row at a time in float over a mirrored-padded copy of the
// frame, so that the loop over x has no border tests and vectorises. demosaic_microgrid and the
// single-pass reduction both run it, so their newton results agree to the reduction's rounding.

#include <cmath>
#include <cstddef>
#include <vector>

namespace tirpol::calibration::detail {

/// How far the Newton stencils reach from a pixel, pixels (own(p ± 2s), other(p ± 3s)).
constexpr int kNewtonReach = 3;

/// The frame as float with kNewtonReach mirrored rows and columns on every side (index −i is i,
/// W − 1 + i is W − 1 − i, as demosaic_microgrid mirrors, which keeps each pixel's analyzer).
/// Row y of the frame starts at data() + (y + 3)·stride() + 3.
class PaddedMosaic {
public:
    template <typename T>
    PaddedMosaic(const T* mosaic, int width, int height)
        : m_stride(static_cast<std::size_t>(width) + 2 * kNewtonReach),
          m_data(m_stride * (static_cast<std::size_t>(height) + 2 * kNewtonReach)) {
        for (int py = 0; py < height + 2 * kNewtonReach; ++py) {
            const T* row = mosaic + static_cast<std::size_t>(mirror(py - kNewtonReach, height)) *
                                        static_cast<std::size_t>(width);
            float* out = m_data.data() + static_cast<std::size_t>(py) * m_stride;
            for (int x = 0; x < width; ++x) out[x + kNewtonReach] = static_cast<float>(row[x]);
            for (int k = 1; k <= kNewtonReach; ++k) {
                out[kNewtonReach - k] = out[kNewtonReach + k];
                out[kNewtonReach + width - 1 + k] = out[kNewtonReach + width - 1 - k];
            }
        }
    }
    /// Padded row y + offset of the frame (offset in [−3, 3]), pointing at its pixel x = 0.
    const float* row(int y, int offset) const {
        return m_data.data() + static_cast<std::size_t>(y + kNewtonReach + offset) * m_stride +
               kNewtonReach;
    }

private:
    static int mirror(int i, int n) {
        if (i < 0) return -i;
        if (i >= n) return 2 * (n - 1) - i;
        return i;
    }
    std::size_t m_stride;
    std::vector<float> m_data;
};

/// ε of the edge weights: 1 % of the frame's mean |value| (plus 10⁻³⁰, so that an all-zero frame
/// stays finite). It keeps flat, noise-free regions in the symmetric branch and sets the scale
/// below which a variation is not an edge.
template <typename T>
float newton_epsilon(const T* mosaic, std::size_t n) {
    double mean_abs = 0.0;
    for (std::size_t i = 0; i < n; ++i) mean_abs += std::abs(static_cast<double>(mosaic[i]));
    return static_cast<float>(1e-2 * (mean_abs / static_cast<double>(n)) + 1e-30);
}

/// Row y of the padded frame: per x, the estimates at (x, y) of the analyzer of the horizontal
/// neighbour (cell position own ^ 1), the vertical one (own ^ 2) and the diagonal one (own ^ 3).
void newton_row(const PaddedMosaic& frame, int y, std::size_t width, float epsilon,
                float* horizontal, float* vertical, float* diagonal);

}  // namespace tirpol::calibration::detail
