#pragma once
// The `tirpol` command line: one CLI11 app, one file per subcommand. Each subcommand file registers
// itself with TIRPOL_REGISTER_COMMAND(order, function) where function(CLI::App&) adds the subcommand
// and its callback; `order` sorts the --help listing (pipeline order). No central list to edit.

#include <CLI/CLI.hpp>
#include <functional>

namespace tirpol::cli {

/// Exit codes (docs/cli.md): 0 success, 1 error in the input or a device, 2 bad command-line usage.
inline constexpr int kExitOk = 0;
inline constexpr int kExitError = 1;
inline constexpr int kExitUsage = 2;

int run(int argc, char** argv);

using CommandRegistration = std::function<void(CLI::App&)>;
/// Adds a subcommand registration; returns true so it can initialise a static.
bool register_command(int order, CommandRegistration registration);

}  // namespace tirpol::cli

#define TIRPOL_CONCAT_INNER(a, b) a##b
#define TIRPOL_CONCAT(a, b) TIRPOL_CONCAT_INNER(a, b)
#define TIRPOL_REGISTER_COMMAND(order, function) \
    static const bool TIRPOL_CONCAT(tirpol_command_registered_, __LINE__) = \
        ::tirpol::cli::register_command(order, function)
