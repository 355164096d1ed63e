#pragma once
// Splitting and number parsing shared by the EPW and field-log CSV readers (private header).

#include <string>
#include <string_view>
#include <vector>

namespace tirpol::thermal::detail {

/// Fields of one comma-separated line (no quoting: neither format quotes numbers); trailing '\r'
/// dropped.
std::vector<std::string> split_csv_line(std::string_view line);

/// Parses a whole field as a number; throws tirpol::Error "<where>: <field> '<text>' is not a
/// number".
double parse_number(const std::string& text, const std::string& where, std::string_view field);

}  // namespace tirpol::thermal::detail
