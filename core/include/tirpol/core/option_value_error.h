#pragma once
/// \file option_value_error.h
/// A value a user gave for a command-line option that the library found wrong once it had read the
/// files the value refers to (a time in a site's offset, a name in a file's list). The CLI exits
/// 2 with it, as a usage error naming the option, instead of 1 for a bad input file. And the one
/// parser of numbers in option values, with the table of option ranges (docs/cli.md lists it).

#include <optional>
#include <string>
#include <string_view>

#include "tirpol/core/error.h"

namespace tirpol {

class OptionValueError : public Error {
public:
    /// `message` may begin with `option` already; the CLI then prints it once.
    OptionValueError(std::string option, const std::string& message)
        : Error(message), m_option(std::move(option)) {}
    /// The option ("--at").
    const std::string& option() const { return m_option; }

private:
    std::string m_option;
};

/// All of `text` as one number in strtod's syntax (as CLI11 converts option values), or nullopt
/// when `text` is empty or not all number. A value beyond a double's range is ±inf.
std::optional<double> parse_number(std::string_view text);

/// The range [lo, hi] the limits table (from core/limits.h) gives an option's values.
struct OptionLimit {
    double lo, hi;
    std::string why;  ///< what the range is, for the message
};

/// The limit of option `long_name` ("--band-um") in subcommand `subcommand` ("planck", "calibrate
/// radiometric"), or of that option in every subcommand, or nullptr.
const OptionLimit* option_limit(const std::string& subcommand, const std::string& long_name);

/// Why `text` is refused as a value of a numeric option with `limit` (nullptr: none): not finite,
/// or outside the limit. Empty when it is accepted, and when it is no number at all (the option
/// parser reports that itself).
std::string option_number_problem(const std::string& text, const OptionLimit* limit);

}  // namespace tirpol
