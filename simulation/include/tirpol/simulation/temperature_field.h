#pragma once
/// \file temperature_field.h
/// The temperature of an object's surface: one value, per-vertex values (interpolated across each
/// triangle) or a texture map looked up by the surface's (u, v). The thermal solver of a later
/// issue fills the same per-vertex form.

#include <vector>

#include "tirpol/core/image.h"
#include "tirpol/simulation/ray_tracer.h"

namespace tirpol::simulation {

class TemperatureField {
public:
    static TemperatureField constant(double temperature_k);
    /// One temperature per mesh vertex, in the mesh's vertex order.
    static TemperatureField per_vertex(std::vector<double> temperatures_k);
    /// A map (row-major, `width` × `height`, kelvin) looked up at texture coordinates (u, v): u
    /// across the columns, v down the rows (v = 0 is the top row). Bilinear, clamped at the edges.
    static TemperatureField texture(std::vector<float> map_k, int width, int height);

    /// Temperature at a hit on `mesh` (the hit's object). No exceptions (hot loop).
    double at(const SurfaceHit& hit, const TriangleMesh& mesh) const;

    /// True for a field made by `constant` (then at() is min_k() everywhere): a renderer can
    /// evaluate what depends only on the temperature, such as Planck's law per wavelength, once per
    /// object.
    bool is_constant() const { return m_kind == Kind::Constant; }

    /// Range of the field, for validation and reports.
    double min_k() const;
    double max_k() const;

private:
    enum class Kind { Constant, PerVertex, Texture };
    Kind m_kind = Kind::Constant;
    double m_constant_k = 0.0;
    std::vector<double> m_vertex_k;
    std::vector<float> m_map_k;
    int m_width = 0, m_height = 0;
};

}  // namespace tirpol::simulation
