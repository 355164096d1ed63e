#pragma once
/// \file csv_columns.h
/// Numeric columns of a small CSV file by header name (sky tables, per-vertex temperatures).

#include <filesystem>
#include <string>
#include <vector>

namespace tirpol::simulation {

/// Reads the named columns of a CSV whose first non-comment line is a header ('#' lines and blank
/// lines skipped, other columns ignored). Errors name the file, line and column.
std::vector<std::vector<double>> read_csv_columns(const std::filesystem::path& path,
                                                  const std::vector<std::string>& columns);

}  // namespace tirpol::simulation
