#pragma once
// The one numeric-option parser of the command line. Every option whose value CLI11 converts to a
// number (type FLOAT, INT or UINT, single or a list) gets a validator: NaN, ±inf and a value that
// overflows a double are usage errors naming the option; options named in the limits table
// (numeric_options.cpp, from core/limits.h) must also lie in their range. Applied once to the whole
// command tree after every subcommand registered itself, so a new option cannot miss it.

#include <CLI/CLI.hpp>
#include <string>

namespace tirpol::cli {

/// The range the limits table gives an option's values, [lo, hi], or none.
struct OptionLimit {
    double lo, hi;
    std::string why;  ///< what the range is, for the message
};

/// The limit of option `long_name` ("--band-um") in subcommand `subcommand` ("planck"), or nullptr.
const OptionLimit* option_limit(const std::string& subcommand, const std::string& long_name);

/// Adds the finite-number and table-range validators to every numeric option of `app` and its
/// subcommands (recursively).
void validate_numeric_options(CLI::App& app);

/// A number written inside an option's text value (e.g. `--bound sigma=0.05:0.8`): the whole text
/// must be a finite number, else a usage error of `option`.
double parse_finite_number(const std::string& text, const std::string& option);

}  // namespace tirpol::cli
