#include <algorithm>
#include <cmath>

#include "tirpol/core/error.h"
#include "tirpol/simulation/scene.h"

namespace tirpol::simulation {

TemperatureField TemperatureField::constant(double temperature_k) {
    TemperatureField f;
    f.m_kind = Kind::Constant;
    f.m_constant_k = temperature_k;
    return f;
}

TemperatureField TemperatureField::per_vertex(std::vector<double> temperatures_k) {
    if (temperatures_k.empty()) fail("per-vertex temperatures: no values");
    TemperatureField f;
    f.m_kind = Kind::PerVertex;
    f.m_vertex_k = std::move(temperatures_k);
    return f;
}

TemperatureField TemperatureField::texture(std::vector<float> map_k, int width, int height) {
    if (width < 1 || height < 1 ||
        map_k.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
        fail("temperature texture: {} values do not fill {}x{}", map_k.size(), width, height);
    TemperatureField f;
    f.m_kind = Kind::Texture;
    f.m_map_k = std::move(map_k);
    f.m_width = width;
    f.m_height = height;
    return f;
}

double TemperatureField::at(const SurfaceHit& hit, const TriangleMesh& mesh) const {
    switch (m_kind) {
        case Kind::Constant:
            return m_constant_k;
        case Kind::PerVertex: {
            const auto& tri = mesh.triangles[hit.primitive];
            return (1.0 - hit.b1 - hit.b2) * m_vertex_k[tri[0]] + hit.b1 * m_vertex_k[tri[1]] +
                   hit.b2 * m_vertex_k[tri[2]];
        }
        case Kind::Texture: {
            const double x = std::clamp(hit.uv.x(), 0.0, 1.0) * m_width - 0.5;
            const double y = std::clamp(hit.uv.y(), 0.0, 1.0) * m_height - 0.5;
            const int x0 = std::clamp(static_cast<int>(std::floor(x)), 0, m_width - 1);
            const int y0 = std::clamp(static_cast<int>(std::floor(y)), 0, m_height - 1);
            const int x1 = std::min(x0 + 1, m_width - 1), y1 = std::min(y0 + 1, m_height - 1);
            const double fx = std::clamp(x - x0, 0.0, 1.0), fy = std::clamp(y - y0, 0.0, 1.0);
            auto v = [&](int xi, int yi) {
                return static_cast<double>(
                    m_map_k[static_cast<std::size_t>(yi) * static_cast<std::size_t>(m_width) +
                            static_cast<std::size_t>(xi)]);
            };
            return (1 - fy) * ((1 - fx) * v(x0, y0) + fx * v(x1, y0)) +
                   fy * ((1 - fx) * v(x0, y1) + fx * v(x1, y1));
        }
    }
    return m_constant_k;
}

double TemperatureField::min_k() const {
    switch (m_kind) {
        case Kind::PerVertex:
            return *std::min_element(m_vertex_k.begin(), m_vertex_k.end());
        case Kind::Texture:
            return *std::min_element(m_map_k.begin(), m_map_k.end());
        default:
            return m_constant_k;
    }
}

double TemperatureField::max_k() const {
    switch (m_kind) {
        case Kind::PerVertex:
            return *std::max_element(m_vertex_k.begin(), m_vertex_k.end());
        case Kind::Texture:
            return *std::max_element(m_map_k.begin(), m_map_k.end());
        default:
            return m_constant_k;
    }
}

}  // namespace tirpol::simulation
