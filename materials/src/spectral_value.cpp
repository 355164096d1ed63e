#include <cmath>
#include <limits>

#include "interpolation.h"
#include "tirpol/core/config.h"
#include "tirpol/core/error.h"
#include "tirpol/materials/microfacet.h"

namespace tirpol::materials {

SpectralValue::SpectralValue(double value) : m_constant(value) {}

SpectralValue::SpectralValue(std::vector<double> wavelength_um, std::vector<double> value,
                             const std::string& what)
    : m_wavelength_um(std::move(wavelength_um)), m_value(std::move(value)) {
    if (m_wavelength_um.size() != m_value.size() || m_wavelength_um.size() < 2)
        fail("{}: expected wavelength_um and value lists of the same length (≥ 2), got {} and {}",
             what, m_wavelength_um.size(), m_value.size());
    for (std::size_t i = 1; i < m_wavelength_um.size(); ++i)
        if (!(m_wavelength_um[i] > m_wavelength_um[i - 1]))
            fail("{}: wavelength_um must increase strictly ({} after {})", what, m_wavelength_um[i],
                 m_wavelength_um[i - 1]);
}

SpectralValue SpectralValue::from_config(const ConfigNode& node, double lo, double hi) {
    auto check = [&](double v) {
        if (!std::isfinite(v) || v < lo || v > hi)
            node.fail(fmt::format("value {} is outside the allowed range [{}, {}]", v, lo, hi));
    };
    if (node.is_scalar()) {
        const double v = node.as<double>();
        check(v);
        return SpectralValue(v);
    }
    if (!node.is_map())
        node.fail("expected a number or a mapping {wavelength_um: [...], value: [...]}");
    node.check_keys({"wavelength_um", "value"});
    auto values = node.get<std::vector<double>>("value");
    for (double v : values) check(v);
    return SpectralValue(node.get<std::vector<double>>("wavelength_um"), std::move(values),
                         node.location() + " (" + node.path() + ")");
}

double SpectralValue::at(double wavelength_um) const {
    return is_constant() ? m_constant
                         : detail::interpolate_linear(m_wavelength_um, m_value, wavelength_um);
}

bool SpectralValue::covers(double lo_um, double hi_um) const {
    if (is_constant()) return true;
    const double slack = 1e-9 * m_wavelength_um.back();
    return lo_um >= m_wavelength_um.front() - slack && hi_um <= m_wavelength_um.back() + slack;
}

double SpectralValue::min_wavelength_um() const {
    return is_constant() ? 0.0 : m_wavelength_um.front();
}
double SpectralValue::max_wavelength_um() const {
    return is_constant() ? std::numeric_limits<double>::infinity() : m_wavelength_um.back();
}

}  // namespace tirpol::materials
