#include "csv_columns.h"

#include <charconv>
#include <sstream>

#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/limits.h"

namespace tirpol::simulation {

namespace {
std::vector<std::string> split_fields(const std::string& line) {
    std::vector<std::string> fields;
    std::stringstream ss(line);
    std::string field;
    while (std::getline(ss, field, ',')) {
        const auto a = field.find_first_not_of(" \t\r"), b = field.find_last_not_of(" \t\r");
        fields.push_back(a == std::string::npos ? std::string() : field.substr(a, b - a + 1));
    }
    return fields;
}
}  // namespace

std::vector<std::vector<double>> read_csv_columns(const std::filesystem::path& path,
                                                  const std::vector<std::string>& columns) {
    const std::string text = read_file(path);
    std::stringstream in(text);
    std::string line;
    int line_no = 0;
    std::vector<std::size_t> index;
    std::vector<std::vector<double>> out(columns.size());
    while (std::getline(in, line)) {
        ++line_no;
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#') continue;
        const auto fields = split_fields(line);
        if (index.empty()) {
            for (const auto& c : columns) {
                std::size_t i = 0;
                while (i < fields.size() && fields[i] != c) ++i;
                if (i == fields.size())
                    fail("{}:{}: header has no column '{}' (expected columns: {})", path.string(),
                         line_no, c, fmt::join(columns, ", "));
                index.push_back(i);
            }
            continue;
        }
        if (out.front().size() == limits::kMaxCsvRows)
            fail("{}:{}: more than {} data rows; tirpol reads tables up to that size",
                 path.string(), line_no, limits::kMaxCsvRows);
        for (std::size_t c = 0; c < columns.size(); ++c) {
            if (index[c] >= fields.size())
                fail("{}:{}: missing value for column '{}'", path.string(), line_no, columns[c]);
            const std::string& f = fields[index[c]];
            double v = 0.0;
            const auto [ptr, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
            if (ec != std::errc() || ptr != f.data() + f.size())
                fail("{}:{}: column '{}': expected a number, got \"{}\"", path.string(), line_no,
                     columns[c], f);
            out[c].push_back(v);
        }
    }
    if (index.empty())
        fail("{}: no header line (expected columns: {})", path.string(), fmt::join(columns, ", "));
    if (out.front().empty()) fail("{}: no data rows", path.string());
    return out;
}

}  // namespace tirpol::simulation
