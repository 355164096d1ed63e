#pragma once
// Every option whose value CLI11 converts to a number (type FLOAT, INT or UINT, single or a list)
// gets a validator: NaN, ±inf and a value that overflows a double are usage errors naming the
// option, and options of the limits table must lie in their range (tirpol::option_number_problem,
// core/option_value_error.h). Applied once to the whole command tree after every subcommand
// registered itself, so a new option cannot miss it.

#include <CLI/CLI.hpp>

namespace tirpol::cli {

/// Adds the finite-number and table-range validators to every numeric option of `app` and its
/// subcommands (recursively).
void validate_numeric_options(CLI::App& app);

}  // namespace tirpol::cli
