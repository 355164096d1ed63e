#include "csv_fields.h"

#include <charconv>

#include "tirpol/core/error.h"

namespace tirpol::thermal::detail {

std::vector<std::string> split_csv_line(std::string_view line) {
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    std::vector<std::string> fields;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = line.find(',', start);
        std::string_view field = line.substr(
            start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
        while (!field.empty() && (field.front() == ' ' || field.front() == '\t'))
            field.remove_prefix(1);
        while (!field.empty() && (field.back() == ' ' || field.back() == '\t'))
            field.remove_suffix(1);
        fields.emplace_back(field);
        if (comma == std::string_view::npos) break;
        start = comma + 1;
    }
    return fields;
}

double parse_number(const std::string& text, const std::string& where, std::string_view field) {
    double value = 0.0;
    const char* begin = text.data();
    const char* end = text.data() + text.size();
    if (!text.empty() && *begin == '+') ++begin;
    const auto [ptr, ec] = std::from_chars(begin, end, value);
    if (text.empty() || ec != std::errc() || ptr != end)
        fail("{}: {} '{}' is not a number", where, field, text);
    return value;
}

}  // namespace tirpol::thermal::detail
