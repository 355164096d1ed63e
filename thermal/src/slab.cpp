#include <algorithm>
#include <cmath>

#include "tirpol/core/error.h"
#include "tirpol/thermal/sky_longwave.h"
#include "tirpol/thermal/surface_temperature.h"

namespace tirpol::thermal {

namespace {
// Incropera, DeWitt, Bergman & Lavine, Fundamentals of Heat and Mass Transfer, 6th ed., Table A.3
// "Soil".
constexpr Layer kSoil{1.0, 0.52, 2050.0, 1840.0, 0};
constexpr int kMaxNewtonIterations = 50;
constexpr double kNewtonToleranceK = 1e-10;
}  // namespace

SurfaceFluxes surface_fluxes(const SurfaceForcing& f, double ts) {
    const double t2 = ts * ts;
    SurfaceFluxes q;
    q.absorbed_shortwave = f.absorbed_shortwave_w_m2;
    q.absorbed_longwave = f.emissivity * f.incident_longwave_w_m2;
    q.emitted_longwave = f.emissivity * kStefanBoltzmann * t2 * t2;
    q.convection = f.convection_w_m2_k * (f.air_temperature_k - ts);
    return q;
}

SlabModel::SlabModel(const SlabDefinition& def, const SlabGridOptions& grid) {
    if (def.layers.empty()) fail("thermal slab: no layers");
    if (!(grid.max_cell_thickness_m > 0.0))
        fail("thermal slab: max cell thickness must be positive");
    std::vector<Layer> layers = def.layers;
    if (def.back.kind == BackBoundary::Kind::Ground) {
        Layer soil = kSoil;
        soil.thickness_m = def.back.ground_depth_m;
        layers.push_back(soil);
    }
    std::vector<double> dx, k;
    for (std::size_t i = 0; i < layers.size(); ++i) {
        const Layer& l = layers[i];
        if (!(l.thickness_m > 0.0 && l.conductivity_w_m_k > 0.0 && l.density_kg_m3 > 0.0 &&
              l.specific_heat_j_kg_k > 0.0))
            fail(
                "thermal slab: layer {} needs positive thickness, conductivity, density and "
                "specific heat "
                "(got {} m, {} W/m·K, {} kg/m³, {} J/kg·K)",
                i + 1, l.thickness_m, l.conductivity_w_m_k, l.density_kg_m3,
                l.specific_heat_j_kg_k);
        const int n = l.cells > 0
                          ? l.cells
                          : std::max(2, static_cast<int>(std::ceil(
                                            l.thickness_m / grid.max_cell_thickness_m - 1e-9)));
        for (int c = 0; c < n; ++c) {
            dx.push_back(l.thickness_m / n);
            k.push_back(l.conductivity_w_m_k);
            m_capacity.push_back(l.density_kg_m3 * l.specific_heat_j_kg_k * l.thickness_m / n);
        }
    }
    const std::size_t n = dx.size();
    m_conductance.resize(n);
    m_depth.resize(n);
    m_conductance[0] = 2.0 * k[0] / dx[0];
    double depth = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
        m_depth[j] = depth + 0.5 * dx[j];
        depth += dx[j];
        // Harmonic (series) conductance across a face between cells of different layers.
        if (j > 0) m_conductance[j] = 1.0 / (0.5 * dx[j - 1] / k[j - 1] + 0.5 * dx[j] / k[j]);
    }
    m_back_fixed = def.back.kind != BackBoundary::Kind::Adiabatic;
    m_back_conductance = m_back_fixed ? 2.0 * k[n - 1] / dx[n - 1] : 0.0;
    m_back_temperature_k = def.back.temperature_k;
    m_t.assign(n, 293.15);
    m_surface_k = 293.15;
    m_a.resize(n + 1);
    m_b.resize(n + 1);
    m_c.resize(n + 1);
    m_r.resize(n + 1);
    m_x.resize(n + 1);
    m_bw.resize(n + 1);
    m_rw.resize(n + 1);
}

void SlabModel::set_uniform_temperature(double t) {
    std::fill(m_t.begin(), m_t.end(), t);
    m_surface_k = t;
}

double SlabModel::stored_energy_j_m2() const {
    double e = 0.0;
    for (std::size_t j = 0; j < m_t.size(); ++j) e += m_capacity[j] * m_t[j];
    return e;
}

double SlabModel::temperature_at_depth_k(double z) const {
    if (z <= 0.0) return m_surface_k;
    if (z <= m_depth.front())
        return m_surface_k + (m_t.front() - m_surface_k) * z / m_depth.front();
    const auto it = std::lower_bound(m_depth.begin(), m_depth.end(), z);
    if (it == m_depth.end()) return m_t.back();
    const auto j = static_cast<std::size_t>(it - m_depth.begin());
    const double f = (z - m_depth[j - 1]) / (m_depth[j] - m_depth[j - 1]);
    return m_t[j - 1] + f * (m_t[j] - m_t[j - 1]);
}

StepReport SlabModel::step(double dt, const SurfaceForcing& forcing, double implicit_weight) {
    const std::size_t n = m_t.size();
    const double explicit_w = 1.0 - implicit_weight;
    // Old-level conduction fluxes through each face (face j is in front of cell j; face n is the
    // back).
    auto face_flux = [&](std::size_t j, double ts, const std::vector<double>& t) {
        if (j == 0) return m_conductance[0] * (ts - t[0]);
        if (j == n)
            return m_back_fixed ? m_back_conductance * (t[n - 1] - m_back_temperature_k) : 0.0;
        return m_conductance[j] * (t[j - 1] - t[j]);
    };
    const double old_front = face_flux(0, m_surface_k, m_t);
    const double old_back = face_flux(n, m_surface_k, m_t);

    // Cell rows (unknown j+1 is cell j); they do not change during the Newton iterations.
    for (std::size_t j = 0; j < n; ++j) {
        const double k_in = m_conductance[j];
        const double k_out = j + 1 < n ? m_conductance[j + 1] : m_back_conductance;
        const double cap = m_capacity[j] / dt;
        m_a[j + 1] = -implicit_weight * k_in;
        m_b[j + 1] = cap + implicit_weight * (k_in + k_out);
        m_c[j + 1] = j + 1 < n ? -implicit_weight * k_out : 0.0;
        double rhs = cap * m_t[j] + explicit_w * (face_flux(j, m_surface_k, m_t) -
                                                  face_flux(j + 1, m_surface_k, m_t));
        if (j + 1 == n && m_back_fixed)
            rhs += implicit_weight * m_back_conductance * m_back_temperature_k;
        m_r[j + 1] = rhs;
    }

    StepReport report;
    double ts = m_surface_k;
    for (int it = 0; it < kMaxNewtonIterations; ++it) {
        // Surface row: linearised balance q(T*) + q'(T*)(T_s − T*) = K0 (T_s − T_0) (or T_s
        // prescribed).
        m_a[0] = 0.0;
        if (forcing.prescribed_surface_temperature_k) {
            m_b[0] = 1.0;
            m_c[0] = 0.0;
            m_r[0] = *forcing.prescribed_surface_temperature_k;
        } else {
            const double q = surface_fluxes(forcing, ts).net();
            const double dq = -4.0 * forcing.emissivity * kStefanBoltzmann * ts * ts * ts -
                              forcing.convection_w_m2_k;
            m_b[0] = m_conductance[0] - dq;
            m_c[0] = -m_conductance[0];
            m_r[0] = q - dq * ts;
        }
        // Thomas algorithm on copies of the diagonal and right-hand side.
        std::copy(m_b.begin(), m_b.end(), m_bw.begin());
        std::copy(m_r.begin(), m_r.end(), m_rw.begin());
        for (std::size_t i = 1; i <= n; ++i) {
            const double w = m_a[i] / m_bw[i - 1];
            m_bw[i] -= w * m_c[i - 1];
            m_rw[i] -= w * m_rw[i - 1];
        }
        m_x[n] = m_rw[n] / m_bw[n];
        for (std::size_t i = n; i-- > 0;) m_x[i] = (m_rw[i] - m_c[i] * m_x[i + 1]) / m_bw[i];
        report.newton_iterations = it + 1;
        const double change = std::abs(m_x[0] - ts);
        ts = m_x[0];
        if (forcing.prescribed_surface_temperature_k || change < kNewtonToleranceK) break;
    }
    m_surface_k = ts;
    for (std::size_t j = 0; j < n; ++j) m_t[j] = m_x[j + 1];
    report.front_flux_w_m2 =
        implicit_weight * face_flux(0, m_surface_k, m_t) + explicit_w * old_front;
    report.back_flux_w_m2 =
        implicit_weight * face_flux(n, m_surface_k, m_t) + explicit_w * old_back;
    return report;
}

}  // namespace tirpol::thermal
