#include <cmath>

#include "tirpol/acquisition/frame_gate.h"
#include "tirpol/core/error.h"

namespace tirpol::acquisition {

void FrameAverager::add(const Frame& frame) {
    const std::size_t n =
        static_cast<std::size_t>(frame.width) * static_cast<std::size_t>(frame.height);
    if (m_count == 0) {
        m_width = frame.width;
        m_height = frame.height;
        m_mean.assign(n, 0.0);
        m_m2.assign(n, 0.0);
    }
    if (frame.width != m_width || frame.height != m_height || frame.counts.size() != n)
        fail("frame {} is {}×{} with {} values; the frames being averaged are {}×{}",
             frame.frame_id, frame.width, frame.height, frame.counts.size(), m_width, m_height);
    ++m_count;
    const double inv_n = 1.0 / static_cast<double>(m_count);
    for (std::size_t i = 0; i < n; ++i) {
        const double x = frame.counts[i];
        const double delta = x - m_mean[i];
        m_mean[i] += delta * inv_n;
        m_m2[i] += delta * (x - m_mean[i]);
    }
}

std::vector<float> FrameAverager::mean() const {
    std::vector<float> out(m_mean.size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<float>(m_mean[i]);
    return out;
}

std::vector<float> FrameAverager::stddev() const {
    std::vector<float> out(m_m2.size(), 0.0f);
    if (m_count < 2) return out;
    const double inv = 1.0 / static_cast<double>(m_count - 1);
    for (std::size_t i = 0; i < out.size(); ++i)
        out[i] = static_cast<float>(std::sqrt(m_m2[i] * inv));
    return out;
}

Image FrameAverager::to_image() const {
    Image image(m_width, m_height);
    image.set_channel("counts", mean());
    image.set_channel("counts_std", stddev());
    image.attributes()["frame_count"] = static_cast<int>(m_count);
    return image;
}

void FrameAverager::reset() { *this = FrameAverager(); }

}  // namespace tirpol::acquisition
