#include "tirpol/materials/emissivity.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include "tirpol/core/error.h"
#include "tirpol/core/quadrature.h"
#include "tirpol/materials/microfacet.h"

namespace tirpol::materials {

StokesVector hemispherical_reflected_stokes(const PolarizedBrdf& brdf, double cos_theta,
                                            double wavelength_um,
                                            const EmissivityOptions& options) {
    const double c = std::clamp(cos_theta, kMinCosine, 1.0);
    const Vec3 wo(std::sqrt(std::max(0.0, 1.0 - c * c)), 0.0, c);
    if (brdf.is_pure_delta()) {
        const BrdfSample s = brdf.quadrature_sample(wo, wavelength_um, 0.5, 0.5);
        return s.pdf > 0.0 ? StokesVector(s.weight.col(0)) : StokesVector(StokesVector::Zero());
    }
    const int order = std::clamp(options.order, 1, 10);
    const QuadratureRule base = gauss_legendre(order);
    // Mirror symmetry (is_isotropic): integrate u2 ∈ [0, ½] with the same node density and double.
    const bool mirror = brdf.is_isotropic();
    const int azimuth_panels =
        std::max(1, mirror ? (options.azimuth_panels + 1) / 2 : options.azimuth_panels);
    const QuadratureRule azimuth = composite_rule(base, azimuth_panels, 0.0, mirror ? 0.5 : 1.0);

    std::vector<double> breaks = brdf.sample_u1_breaks(wo, wavelength_um);
    breaks.insert(breaks.begin(), 0.0);
    breaks.push_back(1.0);

    StokesVector sum = StokesVector::Zero();
    for (std::size_t piece = 0; piece + 1 < breaks.size(); ++piece) {
        if (!(breaks[piece + 1] > breaks[piece])) continue;
        // u = a + (b − a)(1 − (1 − v)²): nodes crowd towards the end of each piece, where the
        // cosine-weighted lobe reaches the horizon (there a volume term ∝ 1/cosθi at grazing view
        // becomes the smooth integrand 2(1 − v)/(1 − v)) and the specular lobe has its slope tail.
        const double a = breaks[piece], width = breaks[piece + 1] - breaks[piece];
        const QuadratureRule radial =
            composite_rule(base, std::max(1, options.radial_panels), 0.0, 1.0);
        for (std::size_t i = 0; i < radial.nodes.size(); ++i) {
            const double one_minus_v = 1.0 - radial.nodes[i];
            const double u1 = a + width * (1.0 - one_minus_v * one_minus_v);
            const double w1 = radial.weights[i] * width * 2.0 * one_minus_v;
            for (std::size_t j = 0; j < azimuth.nodes.size(); ++j) {
                const BrdfSample s =
                    brdf.quadrature_sample(wo, wavelength_um, u1, azimuth.nodes[j]);
                if (!(s.pdf > 0.0)) continue;
                sum += (w1 * azimuth.weights[j]) * s.weight.col(0);
            }
        }
    }
    if (mirror) {
        sum *= 2.0;
        sum(2) = sum(3) = 0.0;
    }
    return sum;
}

StokesVector directional_emissivity(const PolarizedBrdf& brdf, double cos_theta,
                                    double wavelength_um, const EmissivityOptions& options) {
    return unpolarized(1.0) -
           hemispherical_reflected_stokes(brdf, cos_theta, wavelength_um, options);
}

double directional_hemispherical_reflectance(const PolarizedBrdf& brdf, double cos_theta,
                                             double wavelength_um,
                                             const EmissivityOptions& options) {
    return hemispherical_reflected_stokes(brdf, cos_theta, wavelength_um, options)(0);
}

namespace {
constexpr double kHalfPi = 0.5 * kPi;

// Grid coordinate x ∈ [0, 1] of emission angle θ: θ = (π/2)(1 − (1 − x)²).
double grid_coordinate(double theta_rad) {
    return 1.0 - std::sqrt(std::max(0.0, 1.0 - theta_rad / kHalfPi));
}

bool same_parameters(const std::vector<BrdfParameter>& a, const std::vector<BrdfParameter>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i].name != b[i].name || a[i].value != b[i].value) return false;
    return true;
}
}  // namespace

void EmissivityTable::init_grid(int angle_nodes) {
    if (m_wavelengths_um.empty()) fail("EmissivityTable: empty wavelength list");
    if (angle_nodes < 4)
        fail("EmissivityTable: angle_nodes = {}: expected at least 4", angle_nodes);
    for (std::size_t i = 1; i < m_wavelengths_um.size(); ++i)
        if (!(m_wavelengths_um[i] > m_wavelengths_um[i - 1]))
            fail("EmissivityTable: wavelengths must increase ({} µm after {} µm)",
                 m_wavelengths_um[i], m_wavelengths_um[i - 1]);
    const auto n = static_cast<std::size_t>(angle_nodes);
    m_angles_rad.resize(n);
    for (std::size_t j = 0; j < n; ++j) {
        const double x = static_cast<double>(j) / static_cast<double>(n - 1);
        m_angles_rad[j] = kHalfPi * (1.0 - (1.0 - x) * (1.0 - x));
    }
}

EmissivityTable EmissivityTable::from_values(std::vector<double> wavelengths_um, int angle_nodes,
                                             std::vector<StokesVector> values) {
    EmissivityTable table;
    table.m_wavelengths_um = std::move(wavelengths_um);
    table.init_grid(angle_nodes);
    if (values.size() != table.m_wavelengths_um.size() * table.m_angles_rad.size())
        fail("EmissivityTable: {} stored values for {} wavelengths × {} angles", values.size(),
             table.m_wavelengths_um.size(), table.m_angles_rad.size());
    for (const StokesVector& v : values)
        if (!v.allFinite()) fail("EmissivityTable: a stored value is not finite");
    table.m_values = std::move(values);
    return table;
}

EmissivityTable::EmissivityTable(const PolarizedBrdf& brdf, std::vector<double> wavelengths_um,
                                 int angle_nodes, const EmissivityOptions& options)
    : m_wavelengths_um(std::move(wavelengths_um)) {
    init_grid(angle_nodes);
    const auto [lo, hi] = brdf.valid_wavelength_range_um();
    for (const double w : m_wavelengths_um)
        if (w < lo * (1.0 - 1e-9) || w > hi * (1.0 + 1e-9))
            fail("EmissivityTable: wavelength {} µm is outside the {} model's data range {}–{} µm",
                 w, brdf.model(), lo, hi);
    const std::size_t n = m_angles_rad.size();
    m_values.resize(n * m_wavelengths_um.size());
    // Columns whose parameters equal the previous column's are copied afterwards.
    std::vector<bool> reuse(m_wavelengths_um.size(), false);
    std::vector<BrdfParameter> previous;
    for (std::size_t w = 0; w < m_wavelengths_um.size(); ++w) {
        std::vector<BrdfParameter> params = brdf.parameters(m_wavelengths_um[w]);
        reuse[w] = w > 0 && same_parameters(params, previous);
        previous = std::move(params);
    }
    std::vector<std::size_t> jobs;  // flat indices w·n + j of the integrals to compute
    for (std::size_t w = 0; w < m_wavelengths_um.size(); ++w)
        if (!reuse[w])
            for (std::size_t j = 0; j < n; ++j) jobs.push_back(w * n + j);
    std::atomic<std::size_t> next{0};
    auto worker = [&] {
        for (std::size_t k = next++; k < jobs.size(); k = next++) {
            const std::size_t w = jobs[k] / n, j = jobs[k] % n;
            m_values[jobs[k]] = directional_emissivity(brdf, std::cos(m_angles_rad[j]),
                                                       m_wavelengths_um[w], options);
        }
    };
    const std::size_t threads = std::clamp<std::size_t>(std::thread::hardware_concurrency(), 1, 16);
    std::vector<std::thread> pool;
    for (std::size_t t = 1; t < std::min(threads, jobs.size()); ++t) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
    for (std::size_t w = 1; w < m_wavelengths_um.size(); ++w)
        if (reuse[w])
            std::copy_n(m_values.begin() + static_cast<std::ptrdiff_t>((w - 1) * n), n,
                        m_values.begin() + static_cast<std::ptrdiff_t>(w * n));
}

double EmissivityTable::position(double cos_theta) const {
    const double theta = std::acos(std::clamp(cos_theta, 0.0, 1.0));
    return grid_coordinate(theta) * static_cast<double>(m_angles_rad.size() - 1);
}

StokesVector EmissivityTable::at_position(double p, std::size_t wavelength_index) const {
    const std::size_t n = m_angles_rad.size();
    // Cubic Lagrange through the 4 nodes around p (window shifted inwards at the ends).
    const auto i = static_cast<std::size_t>(std::clamp(p, 0.0, static_cast<double>(n - 1)));
    const std::size_t start = std::min(i > 0 ? i - 1 : 0, n - 4);
    const double t = p - static_cast<double>(start);  // position relative to node `start`
    const double l0 = -(t - 1.0) * (t - 2.0) * (t - 3.0) / 6.0;
    const double l1 = t * (t - 2.0) * (t - 3.0) / 2.0;
    const double l2 = -t * (t - 1.0) * (t - 3.0) / 2.0;
    const double l3 = t * (t - 1.0) * (t - 2.0) / 6.0;
    const StokesVector* v = &m_values[wavelength_index * n + start];
    return l0 * v[0] + l1 * v[1] + l2 * v[2] + l3 * v[3];
}

StokesVector EmissivityTable::at(double cos_theta, std::size_t wavelength_index) const {
    return at_position(position(cos_theta),
                       std::min(wavelength_index, m_wavelengths_um.size() - 1));
}

namespace {
// Bracketing columns and the weight of the upper one for wavelength λ (clamped at the ends).
std::pair<std::size_t, double> bracket(const std::vector<double>& wl, double wavelength_um) {
    if (wl.size() == 1 || wavelength_um <= wl.front()) return {0, 0.0};
    if (wavelength_um >= wl.back()) return {wl.size() - 2, 1.0};
    const auto i = static_cast<std::size_t>(std::upper_bound(wl.begin(), wl.end(), wavelength_um) -
                                            wl.begin());
    return {i - 1, (wavelength_um - wl[i - 1]) / (wl[i] - wl[i - 1])};
}
}  // namespace

StokesVector EmissivityTable::at_wavelength(double cos_theta, double wavelength_um) const {
    const double p = position(cos_theta);
    if (m_wavelengths_um.size() == 1) return at_position(p, 0);
    const auto [i, t] = bracket(m_wavelengths_um, wavelength_um);
    return (1.0 - t) * at_position(p, i) + t * at_position(p, i + 1);
}

StokesVector EmissivityTable::band_average(double cos_theta, const Band& band,
                                           double temperature_k) const {
    const double p = position(cos_theta);
    if (m_wavelengths_um.size() == 1) return at_position(p, 0);
    StokesVector num = StokesVector::Zero();
    double den = 0.0;
    for (const BandNode& node : band.nodes()) {
        const double w = node.weight_um * planck_radiance(node.wavelength_um, temperature_k);
        const auto [i, t] = bracket(m_wavelengths_um, node.wavelength_um);
        num += (w * (1.0 - t)) * at_position(p, i) + (w * t) * at_position(p, i + 1);
        den += w;
    }
    return den > 0.0 ? StokesVector(num / den)
                     : at_wavelength(cos_theta, 0.5 * (band.lo_um() + band.hi_um()));
}

std::vector<double> EmissivityTable::band_weights(const Band& band, double temperature_k) const {
    std::vector<double> weights(m_wavelengths_um.size(), 0.0);
    double den = 0.0;
    for (const BandNode& node : band.nodes()) {
        const double w = node.weight_um * planck_radiance(node.wavelength_um, temperature_k);
        if (m_wavelengths_um.size() == 1) {
            weights[0] += w;
        } else {
            const auto [i, t] = bracket(m_wavelengths_um, node.wavelength_um);
            weights[i] += w * (1.0 - t);
            weights[i + 1] += w * t;
        }
        den += w;
    }
    if (den > 0.0)
        for (double& w : weights) w /= den;
    return weights;
}

StokesVector EmissivityTable::at_weighted(double cos_theta,
                                          const std::vector<double>& weights) const {
    const double p = position(cos_theta);
    StokesVector sum = StokesVector::Zero();
    const std::size_t n = std::min(weights.size(), m_wavelengths_um.size());
    for (std::size_t w = 0; w < n; ++w)
        if (weights[w] != 0.0) sum += weights[w] * at_position(p, w);
    return sum;
}

std::vector<double> EmissivityTable::wavelengths_for_band(const Band& band, double step_um) {
    const double width = band.hi_um() - band.lo_um();
    const int steps = std::max(1, static_cast<int>(std::ceil(width / step_um - 1e-9)));
    std::vector<double> out;
    for (int i = 0; i <= steps; ++i) out.push_back(band.lo_um() + width * i / steps);
    return out;
}

}  // namespace tirpol::materials
