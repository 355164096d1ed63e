#pragma once
/// \file image.h
/// A multi-channel float image with typed header attributes: the in-memory form of every EXR tirpol
/// reads or writes. Row-major, origin top-left, channels stored as separate planes.

#include <cstddef>
#include <map>
#include <string>
#include <variant>
#include <vector>

namespace tirpol {

/// A header attribute: integer, real, text or a list of reals (EXR int, double, string,
/// floatvector).
using AttributeValue = std::variant<int, double, std::string, std::vector<double>>;
using Attributes = std::map<std::string, AttributeValue>;

class Image {
public:
    Image() = default;
    Image(int width, int height);

    int width() const { return m_width; }
    int height() const { return m_height; }
    std::size_t pixel_count() const {
        return static_cast<std::size_t>(m_width) * static_cast<std::size_t>(m_height);
    }

    /// Adds a channel filled with `value`; throws tirpol::Error if it exists. Returns its plane.
    std::vector<float>& add_channel(const std::string& name, float value = 0.0f);
    /// Adds or replaces a channel with `data` (must hold pixel_count() values).
    void set_channel(const std::string& name, std::vector<float> data);
    bool has_channel(const std::string& name) const;
    /// The plane of channel `name`; throws tirpol::Error naming the missing channel and those
    /// present.
    const std::vector<float>& channel(const std::string& name) const;
    std::vector<float>& channel(const std::string& name);
    /// Channel names in the order they were added.
    const std::vector<std::string>& channel_names() const { return m_names; }

    float at(const std::string& name, int x, int y) const { return channel(name)[index(x, y)]; }
    std::size_t index(int x, int y) const {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(m_width) +
               static_cast<std::size_t>(x);
    }

    Attributes& attributes() { return m_attributes; }
    const Attributes& attributes() const { return m_attributes; }

private:
    int m_width = 0;
    int m_height = 0;
    std::vector<std::string> m_names;
    std::map<std::string, std::vector<float>> m_planes;
    Attributes m_attributes;
};

/// Per-channel statistics over finite values.
struct ChannelStats {
    double min = 0.0, mean = 0.0, max = 0.0, std = 0.0;
    std::size_t finite_count = 0, nan_count = 0, inf_count = 0;
};
ChannelStats channel_stats(const std::vector<float>& plane);

}  // namespace tirpol
