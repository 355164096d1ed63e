#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>

#include "interpolation.h"
#include "tirpol/core/config.h"
#include "tirpol/core/error.h"
#include "tirpol/core/output_guard.h"
#include "tirpol/materials/fresnel.h"

namespace tirpol::materials {

namespace {

struct Rows {
    std::vector<double> wavelength_um;
    std::vector<std::vector<double>> columns;
};

// Parses whitespace-separated numeric rows ("λ n k" or "λ v") of a refractiveindex.info `data:`
// block.
Rows parse_rows(const std::string& block, std::size_t expected_columns, const std::string& where) {
    Rows rows;
    rows.columns.resize(expected_columns - 1);
    std::istringstream in(block);
    std::string line;
    int line_no = 0;
    while (std::getline(in, line)) {
        ++line_no;
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        std::istringstream fields(line);
        std::vector<double> values;
        double v;
        while (fields >> v) values.push_back(v);
        if (!fields.eof() || values.size() != expected_columns)
            fail("{}: data row {} \"{}\": expected {} numbers", where, line_no, line,
                 expected_columns);
        rows.wavelength_um.push_back(values[0]);
        for (std::size_t c = 1; c < expected_columns; ++c) rows.columns[c - 1].push_back(values[c]);
    }
    return rows;
}

RefractiveIndexTable load_refractiveindex_yaml(const std::filesystem::path& path) {
    const ConfigNode root = ConfigNode::load_file(path);
    const ConfigNode data = root.at("DATA");
    std::optional<Rows> nk, n_only, k_only;
    for (const ConfigNode& entry : data.elements()) {
        const auto type = entry.get<std::string>("type");
        const std::string where = entry.location() + " (" + entry.path() + ")";
        if (type == "tabulated nk") {
            nk = parse_rows(entry.get<std::string>("data"), 3, where);
        } else if (type == "tabulated n") {
            n_only = parse_rows(entry.get<std::string>("data"), 2, where);
        } else if (type == "tabulated k") {
            k_only = parse_rows(entry.get<std::string>("data"), 2, where);
        } else {
            entry.at("type").fail(
                "unsupported DATA type \"" + type +
                "\" (tirpol reads \"tabulated nk\", \"tabulated n\" and \"tabulated k\"; "
                "tabulate formula data first)");
        }
    }
    const std::string source = path.string();
    if (nk) return RefractiveIndexTable(nk->wavelength_um, nk->columns[0], nk->columns[1], source);
    if (!n_only) data.fail("no \"tabulated nk\" or \"tabulated n\" entry");
    if (!k_only) {
        return RefractiveIndexTable(n_only->wavelength_um, n_only->columns[0],
                                    std::vector<double>(n_only->wavelength_um.size(), 0.0), source);
    }
    // Separate n and k grids: tabulate k on n's grid (inside k's range only).
    std::vector<double> wl, n, k;
    for (std::size_t i = 0; i < n_only->wavelength_um.size(); ++i) {
        const double w = n_only->wavelength_um[i];
        if (w < k_only->wavelength_um.front() || w > k_only->wavelength_um.back()) continue;
        wl.push_back(w);
        n.push_back(n_only->columns[0][i]);
        k.push_back(detail::interpolate_linear(k_only->wavelength_um, k_only->columns[0], w));
    }
    if (wl.size() < 2) data.fail("the n and k tables do not overlap in wavelength");
    return RefractiveIndexTable(wl, n, k, source);
}

constexpr std::size_t kNone = static_cast<std::size_t>(-1);

RefractiveIndexTable load_csv(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) fail("{}: cannot open refractive-index CSV", path.string());
    std::string line;
    int line_no = 0;
    std::size_t col_wl = kNone, col_n = kNone, col_k = kNone;
    std::vector<double> wl, n, k;
    while (std::getline(in, line)) {
        ++line_no;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty() || line[0] == '#') continue;
        std::vector<std::string> cells;
        std::stringstream ss(line);
        std::string cell;
        while (std::getline(ss, cell, ',')) {
            cell.erase(0, cell.find_first_not_of(" \t"));
            cell.erase(cell.find_last_not_of(" \t") + 1);
            cells.push_back(cell);
        }
        if (col_wl == kNone) {
            for (std::size_t c = 0; c < cells.size(); ++c) {
                if (cells[c] == "wavelength_um") col_wl = c;
                if (cells[c] == "n") col_n = c;
                if (cells[c] == "k") col_k = c;
            }
            if (col_wl == kNone || col_n == kNone || col_k == kNone)
                fail("{}:{}: expected a header naming the columns wavelength_um, n, k; got \"{}\"",
                     path.string(), line_no, line);
            continue;
        }
        auto number = [&](std::size_t c, const char* name) {
            if (c >= cells.size()) fail("{}:{}: missing column {}", path.string(), line_no, name);
            try {
                std::size_t used = 0;
                const double v = std::stod(cells[c], &used);
                if (used != cells[c].size()) throw std::invalid_argument(name);
                return v;
            } catch (const std::exception&) {
                fail("{}:{}: {}: expected a number, got \"{}\"", path.string(), line_no, name,
                     cells[c]);
            }
        };
        wl.push_back(number(col_wl, "wavelength_um"));
        n.push_back(number(col_n, "n"));
        k.push_back(number(col_k, "k"));
    }
    if (col_wl == kNone)
        fail("{}: empty refractive-index CSV (expected header wavelength_um,n,k)", path.string());
    return RefractiveIndexTable(wl, n, k, path.string());
}

}  // namespace

RefractiveIndexTable RefractiveIndexTable::constant(ComplexIndex index, std::string source) {
    if (!(index.n > 0.0) || !(index.k >= 0.0) || !std::isfinite(index.n) || !std::isfinite(index.k))
        fail("{}: refractive index n = {}, k = {}: expected n > 0 and k ≥ 0", source, index.n,
             index.k);
    RefractiveIndexTable t;
    t.m_constant = index;
    t.m_source = std::move(source);
    return t;
}

RefractiveIndexTable::RefractiveIndexTable(std::vector<double> wavelength_um, std::vector<double> n,
                                           std::vector<double> k, std::string source)
    : m_wavelength_um(std::move(wavelength_um)),
      m_n(std::move(n)),
      m_k(std::move(k)),
      m_source(std::move(source)) {
    if (m_wavelength_um.size() != m_n.size() || m_n.size() != m_k.size())
        fail("{}: refractive-index table columns have different lengths", m_source);
    if (m_wavelength_um.size() < 2)
        fail("{}: refractive-index table needs at least 2 rows", m_source);
    for (std::size_t i = 0; i < m_wavelength_um.size(); ++i) {
        if (i > 0 && !(m_wavelength_um[i] > m_wavelength_um[i - 1]))
            fail("{}: wavelengths must increase strictly (row {}: {} µm after {} µm)", m_source,
                 i + 1, m_wavelength_um[i], m_wavelength_um[i - 1]);
        if (!(m_n[i] > 0.0) || !(m_k[i] >= 0.0))
            fail("{}: row {} (λ = {} µm): n = {}, k = {}: expected n > 0 and k ≥ 0", m_source,
                 i + 1, m_wavelength_um[i], m_n[i], m_k[i]);
    }
}

RefractiveIndexTable RefractiveIndexTable::load(const std::filesystem::path& path) {
    check_input_file(path);
    const auto ext = path.extension().string();
    if (ext == ".yml" || ext == ".yaml") return load_refractiveindex_yaml(path);
    if (ext == ".csv") return load_csv(path);
    fail(
        "{}: unknown refractive-index file type (expected .yml/.yaml from refractiveindex.info or "
        ".csv)",
        path.string());
}

ComplexIndex RefractiveIndexTable::at(double wavelength_um) const {
    if (!is_constant() && !covers(wavelength_um, wavelength_um))
        fail("{}: wavelength {} µm is outside the table's range {}–{} µm", m_source, wavelength_um,
             m_wavelength_um.front(), m_wavelength_um.back());
    return at_clamped(wavelength_um);
}

ComplexIndex RefractiveIndexTable::at_clamped(double wavelength_um) const {
    if (is_constant()) return m_constant;
    return {detail::interpolate_linear(m_wavelength_um, m_n, wavelength_um),
            detail::interpolate_linear(m_wavelength_um, m_k, wavelength_um)};
}

bool RefractiveIndexTable::covers(double lo_um, double hi_um) const {
    if (is_constant()) return true;
    // A relative slack of 1e-9 accepts end points written with rounding.
    const double slack = 1e-9 * m_wavelength_um.back();
    return lo_um >= m_wavelength_um.front() - slack && hi_um <= m_wavelength_um.back() + slack;
}

double RefractiveIndexTable::min_wavelength_um() const {
    return is_constant() ? 0.0 : m_wavelength_um.front();
}
double RefractiveIndexTable::max_wavelength_um() const {
    return is_constant() ? std::numeric_limits<double>::infinity() : m_wavelength_um.back();
}

}  // namespace tirpol::materials
