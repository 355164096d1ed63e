#include "tirpol/core/image.h"

#include <algorithm>
#include <cmath>

#include "tirpol/core/error.h"
#include "tirpol/core/limits.h"

namespace tirpol {

Image::Image(int width, int height) : m_width(width), m_height(height) {
    if (width <= 0 || height <= 0) fail("image size must be positive, got {}×{}", width, height);
    if (width > limits::kMaxImageSide || height > limits::kMaxImageSide ||
        pixel_count() > limits::kMaxImagePixels)
        fail("image size {}×{} exceeds tirpol's limits ({} pixels a side, {} pixels in all)", width,
             height, limits::kMaxImageSide, limits::kMaxImagePixels);
}

std::vector<float>& Image::add_channel(const std::string& name, float value) {
    if (has_channel(name)) fail("image already has a channel '{}'", name);
    m_names.push_back(name);
    return m_planes[name] = std::vector<float>(pixel_count(), value);
}

void Image::set_channel(const std::string& name, std::vector<float> data) {
    if (data.size() != pixel_count())
        fail("channel '{}' has {} values, the {}×{} image needs {}", name, data.size(), m_width,
             m_height, pixel_count());
    if (!has_channel(name)) m_names.push_back(name);
    m_planes[name] = std::move(data);
}

bool Image::has_channel(const std::string& name) const { return m_planes.count(name) != 0; }

const std::vector<float>& Image::channel(const std::string& name) const {
    auto it = m_planes.find(name);
    if (it == m_planes.end()) {
        std::string present;
        for (const auto& n : m_names) present += (present.empty() ? "" : ", ") + n;
        fail("image has no channel '{}' (channels present: {})", name,
             present.empty() ? "none" : present);
    }
    return it->second;
}

std::vector<float>& Image::channel(const std::string& name) {
    return const_cast<std::vector<float>&>(static_cast<const Image&>(*this).channel(name));
}

ChannelStats channel_stats(const std::vector<float>& plane) {
    ChannelStats s;
    double sum = 0.0, sum2 = 0.0;
    s.min = std::numeric_limits<double>::infinity();
    s.max = -std::numeric_limits<double>::infinity();
    for (float v : plane) {
        if (std::isnan(v)) {
            ++s.nan_count;
            continue;
        }
        if (std::isinf(v)) {
            ++s.inf_count;
            continue;
        }
        ++s.finite_count;
        sum += v;
        sum2 += static_cast<double>(v) * v;
        s.min = std::min(s.min, static_cast<double>(v));
        s.max = std::max(s.max, static_cast<double>(v));
    }
    if (s.finite_count == 0) {
        s.min = s.max = std::numeric_limits<double>::quiet_NaN();
        s.mean = s.std = std::numeric_limits<double>::quiet_NaN();
        return s;
    }
    const auto n = static_cast<double>(s.finite_count);
    s.mean = sum / n;
    s.std = std::sqrt(std::max(0.0, sum2 / n - s.mean * s.mean));
    return s;
}

}  // namespace tirpol
