#pragma once
/// \file frame_averager.h
/// Per-pixel running mean and standard deviation of a frame stream (Welford's online algorithm,
/// B. P. Welford, Technometrics 4(3):419–420, 1962), in double so that 10⁴ frames of 14-bit counts
/// lose nothing. The result is the `counts` / `counts_std` pair of a raw-frame EXR
/// (ARCHITECTURE.md).

#include <cstdint>
#include <vector>

#include "tirpol/acquisition/camera.h"
#include "tirpol/core/image.h"

namespace tirpol::acquisition {

class FrameAverager {
public:
    /// Adds a frame. Throws tirpol::Error if its size differs from the first frame's.
    void add(const Frame& frame);
    std::uint64_t count() const { return m_count; }
    int width() const { return m_width; }
    int height() const { return m_height; }
    /// Mean counts per pixel.
    std::vector<float> mean() const;
    /// Sample standard deviation per pixel (divides by n − 1; 0 for fewer than two frames).
    std::vector<float> stddev() const;
    /// An image with channels `counts` (mean) and `counts_std`, and attribute `frame_count`.
    Image to_image() const;
    void reset();

private:
    int m_width = 0, m_height = 0;
    std::uint64_t m_count = 0;
    std::vector<double> m_mean, m_m2;
};

}  // namespace tirpol::acquisition
