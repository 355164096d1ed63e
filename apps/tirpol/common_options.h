#pragma once
// Declarations and printing shared by many subcommands: one place for the options that several
// subcommands take (--json, -o/--output, --band-um with --rsr, required inputs) and for the
// output every --json prints.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace tirpol::cli {

/// `--json`: print the result as JSON instead of text.
CLI::Option* add_json_flag(CLI::App* command, bool& json,
                           const std::string& description = "Print JSON");

/// A required argument or option naming a file (or, with `exists`, a folder or either) that must
/// exist: a missing one is an error in an input (exit 1, cli.cpp), not a usage error.
template <typename T>
CLI::Option* add_required_input(CLI::App* command, const std::string& name, T& value,
                                const std::string& description,
                                const CLI::Validator& exists = CLI::ExistingFile) {
    return command->add_option(name, value, description)->required()->check(exists);
}

/// `-o,--output PATH`, required.
CLI::Option* add_output_option(CLI::App* command, std::string& output,
                               const std::string& description);

/// `--band-um LO HI` (two values) and `--rsr CSV` (an existing file); returns the band option so a
/// caller can make it required or exclusive.
CLI::Option* add_band_options(CLI::App* command, std::vector<double>& band_um, std::string& rsr);

/// Prints `json` indented by two spaces and a newline to stdout, with invalid UTF-8 replaced.
void print_json(const nlohmann::json& json);

/// Prints `text` to stdout as it is.
void print_text(const std::string& text);

}  // namespace tirpol::cli
