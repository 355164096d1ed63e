// results.csv and results.json (sweep_results.h).

#include <fmt/format.h>

#include <cmath>

#include "records_json.h"
#include "results.h"
#include "tirpol/core/atomic_file.h"

namespace tirpol::sweep::detail {

namespace {

std::string csv_field(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string out = "\"";
    for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

std::string csv_line(const std::vector<std::string>& fields) {
    std::string line;
    for (std::size_t i = 0; i < fields.size(); ++i) line += (i ? "," : "") + csv_field(fields[i]);
    return line + "\n";
}

std::string csv_number(double v) {
    return std::isfinite(v) ? fmt::format("{:.9g}", v) : std::string();
}

void append_values(std::vector<std::string>& row, const QuantityEstimates* q) {
    for (std::size_t i = 0; i < std::size(kQuantityNames); ++i) {
        row.push_back(q ? csv_number(quantity(*q, i).mean) : "");
        row.push_back(q ? csv_number(quantity(*q, i).error) : "");
    }
}

}  // namespace

std::vector<std::filesystem::path> write_tables(const SweepSpec& spec,
                                                const std::filesystem::path& out_dir,
                                                const std::vector<PointRecord>& points) {
    std::vector<std::string> header = {"index", "id", "status"};
    for (const auto& a : spec.axes) header.push_back(a.parameter);
    header.push_back("seed");
    std::vector<std::string> groups;
    for (const auto& r : spec.regions) groups.push_back(r.name);
    for (const auto& c : spec.contrasts) groups.push_back(c.name);
    for (const auto& g : groups)
        for (const char* q : kQuantityNames) {
            header.push_back(g + "." + q);
            header.push_back(g + "." + q + ".error");
        }
    std::string csv = csv_line(header);
    nlohmann::json rows = nlohmann::json::array();
    for (const auto& p : points) {
        std::vector<std::string> row = {std::to_string(p.point.index), p.point.id, p.status};
        for (std::size_t a = 0; a < spec.axes.size(); ++a)
            row.push_back(spec.axes[a].labels[p.point.value_index[a]]);
        row.push_back(std::to_string(p.point.seed));
        const PointStatistics* s = p.statistics ? &*p.statistics : nullptr;
        for (std::size_t i = 0; i < spec.regions.size(); ++i)
            append_values(row, s ? &s->regions[i].values : nullptr);
        for (std::size_t i = 0; i < spec.contrasts.size(); ++i)
            append_values(row, s ? &s->contrasts[i].values : nullptr);
        csv += csv_line(row);
        nlohmann::json j = record_json(spec, p);
        for (const char* timing : {"seconds", "render_seconds", "wait_seconds", "rank"})
            j.erase(timing);
        rows.push_back(std::move(j));
    }
    const std::vector<std::filesystem::path> written = {out_dir / "results.csv",
                                                        out_dir / "results.json"};
    write_file_atomic(written[0], csv);
    write_file_atomic(
        written[1],
        nlohmann::json({{"quantities", kQuantityNames}, {"points", rows}}).dump(2) + "\n");
    return written;
}

}  // namespace tirpol::sweep::detail
