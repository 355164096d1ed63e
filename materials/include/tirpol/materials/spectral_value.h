#pragma once
/// \file spectral_value.h
/// A model parameter that is either a constant or a table over wavelength (µm), linearly
/// interpolated. Material files write either `sigma: 0.3` or `sigma: {wavelength_um: [8, 10, 12],
/// value: [...]}`.

#include <string>
#include <vector>

namespace tirpol {
class ConfigNode;
}

namespace tirpol::materials {

class SpectralValue {
public:
    /// A constant.
    SpectralValue(double value =
                      0.0);  // NOLINT(google-explicit-constructor): a number is a constant spectrum
    /// A table; wavelengths strictly increasing (error otherwise, naming `what`).
    SpectralValue(std::vector<double> wavelength_um, std::vector<double> value,
                  const std::string& what);

    /// Reads `node` (a number or a {wavelength_um, value} mapping); values must lie in [lo, hi].
    static SpectralValue from_config(const ConfigNode& node, double lo, double hi);

    /// Value at a wavelength; clamped to the end values outside a table (check `covers` first).
    double at(double wavelength_um) const;
    bool is_constant() const { return m_wavelength_um.empty(); }
    /// True if [lo, hi] lies in the table's range (always for a constant).
    bool covers(double lo_um, double hi_um) const;
    double min_wavelength_um() const;
    double max_wavelength_um() const;

private:
    std::vector<double> m_wavelength_um, m_value;
    double m_constant = 0.0;
};

}  // namespace tirpol::materials
