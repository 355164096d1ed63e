#include "tirpol/core/emissivity_csv.h"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <sstream>

#include "tirpol/core/error.h"
#include "tirpol/core/limits.h"

namespace tirpol {

namespace {

constexpr const char* kHeader =
    "name,view_angle_deg,temperature_k,pixels,l_dw_w_m2_sr,l_bb_w_m2_sr,frame,eps_s0,eps_s0_std,"
    "eps_s1,eps_s1_std,"
    "eps_s2,eps_s2_std,wavelength_um";

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

// Index of the first of `names` present in the header; -1 if none is.
int find_column(const std::vector<std::string>& header,
                std::initializer_list<std::string_view> names) {
    for (std::string_view name : names) {
        const auto it = std::find(header.begin(), header.end(), name);
        if (it != header.end()) return static_cast<int>(it - header.begin());
    }
    return -1;
}

// An uncertainty column and the factor to 1σ: the current 1σ name, the old 2σ name, or a
// hand-written 1σ.
struct UncertaintyColumn {
    int index = -1;
    double to_std = 1.0;
};

UncertaintyColumn find_uncertainty(const std::vector<std::string>& header,
                                   const std::string& component) {
    if (const int i = find_column(header, {"eps_" + component + "_std"}); i >= 0) return {i, 1.0};
    if (const int i = find_column(header, {"eps_" + component + "_2sigma"}); i >= 0)
        return {i, 0.5};
    return {find_column(header, {"e_" + component + "_sigma"}), 1.0};
}

template <typename T>
std::string optional_cell(const std::optional<T>& value) {
    return value ? fmt::format("{}", *value) : std::string();
}

}  // namespace

std::string_view to_string(EmissivityFrame frame) {
    return frame == EmissivityFrame::Image ? "image" : "plane_of_emission";
}

std::string emissivity_csv_text(const std::vector<EmissivityCsvRow>& rows) {
    std::string out = std::string(kHeader) + '\n';
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const EmissivityCsvRow& r = rows[i];
        if (r.name.find_first_of(",\"\r\n") != std::string::npos)
            fail(
                "emissivity CSV row {}: name \"{}\" contains a comma, quote or line break; "
                "expected a plain name",
                i + 1, r.name);
        out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", r.name, r.view_angle_deg,
                           optional_cell(r.temperature_k), optional_cell(r.pixels),
                           optional_cell(r.l_dw_w_m2_sr), optional_cell(r.l_bb_w_m2_sr),
                           to_string(r.frame), r.eps_s0, r.eps_s0_std, r.eps_s1, r.eps_s1_std,
                           optional_cell(r.eps_s2), optional_cell(r.eps_s2_std),
                           optional_cell(r.wavelength_um));
    }
    return out;
}

std::vector<EmissivityCsvRow> parse_emissivity_csv(const std::string& text,
                                                   const std::string& source) {
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
    if (header.empty()) fail("{}: empty file; expected a CSV header (docs/fitting.md)", source);

    const int c_angle = find_column(header, {"view_angle_deg", "angle_deg"});
    const int c_s0 = find_column(header, {"eps_s0", "e_s0"});
    const int c_s1 = find_column(header, {"eps_s1", "e_s1"});
    const UncertaintyColumn u_s0 = find_uncertainty(header, "s0");
    const UncertaintyColumn u_s1 = find_uncertainty(header, "s1");
    const std::pair<const char*, int> required[] = {
        {"view_angle_deg (or angle_deg)", c_angle},
        {"eps_s0 (or e_s0)", c_s0},
        {"eps_s0_std (or eps_s0_2sigma, e_s0_sigma)", u_s0.index},
        {"eps_s1 (or e_s1)", c_s1},
        {"eps_s1_std (or eps_s1_2sigma, e_s1_sigma)", u_s1.index}};
    for (const auto& [what, index] : required)
        if (index < 0)
            fail(
                "{}:{}: the header has no column {}; expected the CSV of `tirpol "
                "extract-emissivity` "
                "(docs/fitting.md)",
                source, line_no, what);
    const int c_s2 = find_column(header, {"eps_s2", "e_s2"});
    const UncertaintyColumn u_s2 = find_uncertainty(header, "s2");
    const int c_name = find_column(header, {"name"});
    const int c_temperature = find_column(header, {"temperature_k"});
    const int c_pixels = find_column(header, {"pixels"});
    const int c_dw = find_column(header, {"l_dw_w_m2_sr"});
    const int c_bb = find_column(header, {"l_bb_w_m2_sr"});
    const int c_wavelength = find_column(header, {"wavelength_um"});
    const int c_frame = find_column(header, {"frame"});
    // Files from before the frame column: what each old writer meant (header comment).
    const bool hand_written = find_column(header, {"e_s0"}) >= 0;
    const EmissivityFrame old_frame = hand_written || c_wavelength >= 0
                                          ? EmissivityFrame::PlaneOfEmission
                                          : EmissivityFrame::Image;

    std::vector<EmissivityCsvRow> rows;
    while (std::getline(in, line)) {
        ++line_no;
        const std::string t = trim(line);
        if (t.empty() || t.front() == '#') continue;
        if (rows.size() >= limits::kMaxCsvRows)
            fail("{}:{}: more than {} data rows; tirpol reads emissivity tables up to that size",
                 source, line_no, limits::kMaxCsvRows);
        const std::vector<std::string> cells = split_csv_line(t);
        if (cells.size() != header.size())
            fail("{}:{}: {} cells, expected {} as in the header", source, line_no, cells.size(),
                 header.size());
        const auto cell = [&](int column) -> const std::string& {
            return cells[static_cast<std::size_t>(column)];
        };
        const auto number = [&](int column) {
            const std::string& c = cell(column);
            const char* begin = c.c_str();
            char* end = nullptr;
            errno = 0;
            const double v = std::strtod(begin, &end);
            if (c.empty() || end != begin + c.size() || errno == ERANGE)
                fail("{}:{}: column {}: \"{}\" is not a number", source, line_no,
                     header[static_cast<std::size_t>(column)], c);
            return v;
        };
        const auto optional_number = [&](int column) -> std::optional<double> {
            if (column < 0 || cell(column).empty()) return std::nullopt;
            return number(column);
        };
        EmissivityCsvRow r;
        r.line = line_no;
        if (c_name >= 0) r.name = cell(c_name);
        r.view_angle_deg = number(c_angle);
        r.temperature_k = optional_number(c_temperature);
        if (const auto p = optional_number(c_pixels)) {
            if (!(*p >= 0.0 && *p <= 1e15 &&
                  *p == static_cast<double>(static_cast<std::size_t>(*p))))
                fail("{}:{}: column pixels: \"{}\" is not a pixel count", source, line_no,
                     cell(c_pixels));
            r.pixels = static_cast<std::size_t>(*p);
        }
        r.l_dw_w_m2_sr = optional_number(c_dw);
        r.l_bb_w_m2_sr = optional_number(c_bb);
        r.frame = old_frame;
        if (c_frame >= 0) {
            if (cell(c_frame) == "image")
                r.frame = EmissivityFrame::Image;
            else if (cell(c_frame) == "plane_of_emission")
                r.frame = EmissivityFrame::PlaneOfEmission;
            else
                fail("{}:{}: column frame: \"{}\"; expected image or plane_of_emission", source,
                     line_no, cell(c_frame));
        }
        r.eps_s0 = number(c_s0);
        r.eps_s0_std = number(u_s0.index) * u_s0.to_std;
        r.eps_s1 = number(c_s1);
        r.eps_s1_std = number(u_s1.index) * u_s1.to_std;
        r.eps_s2 = optional_number(c_s2);
        if (const auto s = optional_number(u_s2.index)) r.eps_s2_std = *s * u_s2.to_std;
        r.wavelength_um = optional_number(c_wavelength);
        rows.push_back(std::move(r));
    }
    if (rows.empty()) fail("{}: no data rows after the header", source);
    return rows;
}

}  // namespace tirpol
