#include <cmath>
#include <sstream>

#include "tirpol/core/error.h"
#include "tirpol/core/utf8.h"
#include "tirpol/materials/material.h"

namespace tirpol::materials {

namespace {

// A YAML double-quoted scalar (JSON string syntax is valid YAML).
std::string quoted(const std::string& s) { return json_text(nlohmann::json(s)); }

std::string number_list(const std::vector<double>& values) {
    std::string out;
    for (const double v : values) out += fmt::format("{}{}", out.empty() ? "" : ", ", v);
    return "[" + out + "]";
}

void check_finite(const MicrofacetMaterialRecord& m, const char* field, double value) {
    if (!std::isfinite(value))
        fail("material \"{}\": {} = {} cannot be written (expected a finite number)", m.name, field,
             value);
}

}  // namespace

std::string microfacet_material_yaml(const MicrofacetMaterialRecord& m) {
    if (m.name.empty()) fail("material file: the material needs a name");
    if (m.wavelengths_um.empty() || m.n.size() != m.wavelengths_um.size() ||
        m.k.size() != m.wavelengths_um.size())
        fail("material \"{}\": {} wavelengths, {} n and {} k values (expected equal, at least one)",
             m.name, m.wavelengths_um.size(), m.n.size(), m.k.size());
    for (std::size_t i = 0; i < m.wavelengths_um.size(); ++i) {
        check_finite(m, "wavelength_um", m.wavelengths_um[i]);
        check_finite(m, "n", m.n[i]);
        check_finite(m, "k", m.k[i]);
    }
    const std::pair<const char*, double> parameters[] = {
        {"sigma", m.sigma},         {"bias", m.bias},   {"tau_deg", m.tau_deg},
        {"omega_deg", m.omega_deg}, {"rho_d", m.rho_d}, {"rho_v", m.rho_v}};
    for (const auto& [field, value] : parameters) check_finite(m, field, value);

    std::ostringstream out;
    for (const std::string& comment : m.comment_lines) {
        std::istringstream lines(comment);
        for (std::string line; std::getline(lines, line);) out << "# " << line << '\n';
    }
    out << "name: " << quoted(m.name) << '\n';
    out << "source: " << quoted(m.source) << '\n';
    out << "notes: " << quoted(m.notes) << '\n';
    out << "model: microfacet\n";
    if (m.wavelengths_um.size() == 1) {
        out << fmt::format("refractive_index: {{n: {}, k: {}}}\n", m.n[0], m.k[0]);
    } else {
        out << "refractive_index:\n  wavelength_um: " << number_list(m.wavelengths_um)
            << "\n  n: " << number_list(m.n) << "\n  k: " << number_list(m.k) << '\n';
    }
    out << "parameters:\n";
    for (const auto& [field, value] : parameters)
        out << "  " << field << ": " << fmt::format("{}", value) << '\n';
    return out.str();
}

}  // namespace tirpol::materials
