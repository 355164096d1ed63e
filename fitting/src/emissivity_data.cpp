#include "tirpol/fitting/emissivity_data.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>

#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/limits.h"

namespace tirpol::fitting {

namespace {

std::string trim(std::string_view s) {
    const auto b = s.find_first_not_of(" \t\r");
    if (b == std::string_view::npos) return {};
    const auto e = s.find_last_not_of(" \t\r");
    return std::string(s.substr(b, e - b + 1));
}

std::vector<std::string> split_csv_line(const std::string& line) {
    std::vector<std::string> out;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) out.push_back(trim(cell));
    if (!line.empty() && line.back() == ',') out.emplace_back();
    return out;
}

// Column lookup by the first of several accepted names; -1 if none is present.
int find_column(const std::vector<std::string>& header, std::initializer_list<std::string_view> names) {
    for (std::string_view name : names) {
        const auto it = std::find(header.begin(), header.end(), name);
        if (it != header.end()) return static_cast<int>(it - header.begin());
    }
    return -1;
}

struct UncertaintyColumn {
    int index = -1;
    double to_sigma = 1.0;  // 0.5 for a 2σ column
};

UncertaintyColumn find_uncertainty(const std::vector<std::string>& header, std::string_view two_sigma,
                                   std::string_view one_sigma_a, std::string_view one_sigma_b) {
    if (const int i = find_column(header, {two_sigma}); i >= 0) return {i, 0.5};
    return {find_column(header, {one_sigma_a, one_sigma_b}), 1.0};
}

}  // namespace

void validate_dataset(const EmissivityDataset& d) {
    if (!(std::isfinite(d.wavelength_um) && d.wavelength_um > 0.0))
        fail("{}: wavelength_um must be a positive number of micrometres, got {}", d.source, d.wavelength_um);
    if (d.samples.empty()) fail("{}: no emissivity samples", d.source);
    for (std::size_t i = 0; i < d.samples.size(); ++i) {
        const EmissivitySample& s = d.samples[i];
        const std::string which = fmt::format("{}: sample {}{}", d.source, i + 1,
                                              s.name.empty() ? "" : " (\"" + s.name + "\")");
        const std::pair<const char*, double> values[] = {{"angle_deg", s.angle_deg}, {"e_s0", s.e_s0},
                                                         {"e_s0_sigma", s.e_s0_sigma}, {"e_s1", s.e_s1},
                                                         {"e_s1_sigma", s.e_s1_sigma}};
        for (const auto& [field, value] : values)
            if (!std::isfinite(value)) fail("{}: {} is {}; expected a finite number", which, field, value);
        if (s.angle_deg < 0.0 || s.angle_deg > 90.0)
            fail("{}: view angle {}° is outside [0°, 90°] (angles are measured from the surface normal)", which,
                 s.angle_deg);
        // Measured emissivities stray outside [0, 1] by noise only; far outside, the row is not an emissivity.
        constexpr double tol = limits::kEmissivityTolerance;
        if (s.e_s0 < -tol || s.e_s0 > 1.0 + tol)
            fail(
                "{}: e_s0 = {} is outside [{}, {}]; an emissivity lies in [0, 1] (a tolerance of {} is allowed for "
                "measurement noise)",
                which, s.e_s0, -tol, 1.0 + tol, tol);
        if (std::abs(s.e_s1) > 1.0 + tol)
            fail(
                "{}: e_s1 = {} is outside [{}, {}]; a polarized emissivity lies in [-1, 1] (a tolerance of {} is "
                "allowed for measurement noise)",
                which, s.e_s1, -1.0 - tol, 1.0 + tol, tol);
        if (!(s.e_s0_sigma > 0.0) || !(s.e_s1_sigma > 0.0))
            fail("{}: uncertainties must be > 0 (got e_s0_sigma = {}, e_s1_sigma = {}); a zero uncertainty would "
                 "give the sample infinite weight",
                 which, s.e_s0_sigma, s.e_s1_sigma);
    }
}

std::vector<EmissivityDataset> load_emissivity_csv(const std::filesystem::path& path, double default_wavelength_um) {
    const std::string text = read_file(path);
    std::istringstream in(text);
    std::string line;
    int line_no = 0;
    std::vector<std::string> header;
    while (std::getline(in, line)) {
        ++line_no;
        const std::string t = trim(line);
        if (t.empty() || t.front() == '#') continue;
        header = split_csv_line(t);
        break;
    }
    if (header.empty()) fail("{}: empty file; expected a CSV header (docs/fitting.md)", path.string());

    const int c_angle = find_column(header, {"view_angle_deg", "angle_deg"});
    const int c_s0 = find_column(header, {"eps_s0", "e_s0"});
    const int c_s1 = find_column(header, {"eps_s1", "e_s1"});
    const UncertaintyColumn u_s0 = find_uncertainty(header, "eps_s0_2sigma", "eps_s0_sigma", "e_s0_sigma");
    const UncertaintyColumn u_s1 = find_uncertainty(header, "eps_s1_2sigma", "eps_s1_sigma", "e_s1_sigma");
    const int c_name = find_column(header, {"name"});
    const int c_wavelength = find_column(header, {"wavelength_um"});
    const std::pair<const char*, int> required[] = {{"view_angle_deg (or angle_deg)", c_angle},
                                                    {"eps_s0 (or e_s0)", c_s0},
                                                    {"eps_s0_2sigma (or e_s0_sigma)", u_s0.index},
                                                    {"eps_s1 (or e_s1)", c_s1},
                                                    {"eps_s1_2sigma (or e_s1_sigma)", u_s1.index}};
    for (const auto& [what, index] : required)
        if (index < 0)
            fail("{}:{}: the header has no column {}; expected the CSV of `tirpol extract-emissivity` "
                 "(docs/fitting.md)",
                 path.string(), line_no, what);
    if (!(std::isfinite(default_wavelength_um) && default_wavelength_um > 0.0))
        fail("default wavelength must be a positive number of micrometres, got {}", default_wavelength_um);

    std::map<double, EmissivityDataset> by_wavelength;
    std::size_t rows = 0;
    while (std::getline(in, line)) {
        ++line_no;
        const std::string t = trim(line);
        if (t.empty() || t.front() == '#') continue;
        if (++rows > limits::kMaxCsvRows)
            fail("{}:{}: more than {} data rows; tirpol reads emissivity tables up to that size", path.string(),
                 line_no, limits::kMaxCsvRows);
        const std::vector<std::string> cells = split_csv_line(t);
        if (cells.size() != header.size())
            fail("{}:{}: {} cells, expected {} as in the header", path.string(), line_no, cells.size(), header.size());
        auto number = [&](int column) {
            const std::string& cell = cells[static_cast<std::size_t>(column)];
            const char* begin = cell.c_str();
            char* end = nullptr;
            errno = 0;
            const double v = std::strtod(begin, &end);
            if (cell.empty() || end != begin + cell.size() || errno == ERANGE)
                fail("{}:{}: column {}: \"{}\" is not a number", path.string(), line_no,
                     header[static_cast<std::size_t>(column)], cell);
            return v;
        };
        EmissivitySample s;
        s.angle_deg = number(c_angle);
        s.e_s0 = number(c_s0);
        s.e_s0_sigma = number(u_s0.index) * u_s0.to_sigma;
        s.e_s1 = number(c_s1);
        s.e_s1_sigma = number(u_s1.index) * u_s1.to_sigma;
        if (c_name >= 0) s.name = cells[static_cast<std::size_t>(c_name)];
        const double wavelength = c_wavelength >= 0 ? number(c_wavelength) : default_wavelength_um;
        EmissivityDataset& d = by_wavelength[wavelength];
        d.wavelength_um = wavelength;
        d.source = c_wavelength >= 0 ? fmt::format("{} ({} µm)", path.string(), wavelength) : path.string();
        // Validate row by row so that the message can name the line.
        EmissivityDataset one{fmt::format("{}:{}", path.string(), line_no), wavelength, {s}};
        validate_dataset(one);
        d.samples.push_back(std::move(s));
    }
    if (by_wavelength.empty()) fail("{}: no data rows after the header", path.string());
    std::vector<EmissivityDataset> out;
    for (auto& [wavelength, d] : by_wavelength) out.push_back(std::move(d));
    return out;
}

std::string emissivity_csv(const std::vector<EmissivityDataset>& datasets) {
    std::ostringstream out;
    out.precision(10);
    out << "name,view_angle_deg,temperature_k,pixels,l_dw_w_m2_sr,l_bb_w_m2_sr,eps_s0,eps_s0_2sigma,eps_s1,"
           "eps_s1_2sigma,eps_s2,eps_s2_2sigma,wavelength_um\n";
    for (const EmissivityDataset& d : datasets)
        for (const EmissivitySample& s : d.samples)
            out << s.name << ',' << s.angle_deg << ",,,,," << s.e_s0 << ',' << 2.0 * s.e_s0_sigma << ','
                << s.e_s1 << ',' << 2.0 * s.e_s1_sigma << ",,," << d.wavelength_um << '\n';
    return out.str();
}

}  // namespace tirpol::fitting
