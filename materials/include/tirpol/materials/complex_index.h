#pragma once
/// \file complex_index.h
/// Complex index of refraction ñ = n + i·k of a material relative to the incidence medium (air,
/// taken as 1), as a function of wavelength in micrometres.
///
/// Convention (used by every Fresnel formula in tirpol): plane waves E ∝ exp(i(k·r − ωt)) and
/// ñ = n + i·k with k ≥ 0 for an absorbing medium: the convention of refractiveindex.info, Palik's
/// Handbook of Optical Constants of Solids (1985) and Hale & Querry (1973).

#include <filesystem>
#include <string>
#include <vector>

namespace tirpol::materials {

/// n + i·k; k ≥ 0 means absorption.
struct ComplexIndex {
    double n = 1.0;
    double k = 0.0;
};

/// A tabulated (or constant) complex index, linearly interpolated in wavelength.
class RefractiveIndexTable {
public:
    /// A wavelength-independent index (valid at every wavelength).
    static RefractiveIndexTable constant(ComplexIndex index, std::string source = "constant");

    /// Tabulated values; wavelengths strictly increasing, n > 0, k ≥ 0. `source` names where the
    /// data came from (used in error messages).
    RefractiveIndexTable(std::vector<double> wavelength_um, std::vector<double> n,
                         std::vector<double> k, std::string source);

    /// Loads a refractiveindex.info database file (YAML with `DATA: - type: tabulated nk` and a
    /// `data:` block of "λ_µm n k" rows; also `tabulated n` + `tabulated k` pairs), or a CSV with a
    /// header naming wavelength_um, n, k ('#' comment lines allowed). Chosen by extension
    /// (.yml/.yaml vs .csv). Errors name the file and line.
    static RefractiveIndexTable load(const std::filesystem::path& path);

    /// Index at `wavelength_um`; throws tirpol::Error naming the source and its range outside it.
    ComplexIndex at(double wavelength_um) const;

    /// Index at `wavelength_um`, clamped to the table's ends (for hot loops whose range was checked
    /// with `covers` beforehand). Never throws.
    ComplexIndex at_clamped(double wavelength_um) const;

    /// True if [lo_um, hi_um] lies inside the table's range.
    bool covers(double lo_um, double hi_um) const;

    bool is_constant() const { return m_wavelength_um.empty(); }
    double min_wavelength_um() const;
    double max_wavelength_um() const;
    const std::string& source() const { return m_source; }
    const std::vector<double>& wavelengths_um() const { return m_wavelength_um; }

private:
    RefractiveIndexTable() = default;
    std::vector<double> m_wavelength_um, m_n, m_k;
    ComplexIndex m_constant;
    std::string m_source;
};

}  // namespace tirpol::materials
