#pragma once
// The `tirpol` command line: one CLI11 app, one file per subcommand. Each subcommand file registers
// itself with TIRPOL_REGISTER_COMMAND(order, function) where function(CLI::App&) adds the
// subcommand and its callback; `order` sorts the --help listing (pipeline order). No central list
// to edit.

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <functional>
#include <string>

#include "tirpol/core/error.h"
#include "tirpol/core/output_guard.h"

namespace tirpol::cli {

/// Exit codes (docs/cli.md): 0 success, 1 error in the input or a device, 2 bad command-line usage.
inline constexpr int kExitOk = 0;
inline constexpr int kExitError = 1;
inline constexpr int kExitUsage = 2;

int run(int argc, char** argv);

/// A usage error found after parsing (a value outside its range, options that conflict or need each
/// other): exit 2 with CLI11's "OPTION: message" and "Run with --help", like CLI11's own checks.
template <typename... Args>
[[noreturn]] void usage_error(const std::string& option, fmt::format_string<Args...> format,
                              Args&&... args) {
    throw CLI::ValidationError(option, fmt::format(format, std::forward<Args>(args)...));
}

/// The `--force` flag of a command that writes: existing files at its outputs may be replaced (its
/// inputs never; tirpol::OutputGuard). Every writing subcommand adds it and passes it to
/// OutputGuard::check() before any work; an OutputConflict exits 2 (cli.cpp).
inline CLI::Option* add_force_flag(CLI::App* command, bool& force) {
    return command->add_flag(
        "--force", force,
        "Replace existing files at the outputs (an input is never replaced; docs/cli.md)");
}

using CommandRegistration = std::function<void(CLI::App&)>;
/// Adds a subcommand registration; returns true so it can initialise a static.
bool register_command(int order, CommandRegistration registration);

}  // namespace tirpol::cli

#define TIRPOL_CONCAT_INNER(a, b) a##b
#define TIRPOL_CONCAT(a, b) TIRPOL_CONCAT_INNER(a, b)
#define TIRPOL_REGISTER_COMMAND(order, function)                            \
    static const bool TIRPOL_CONCAT(tirpol_command_registered_, __LINE__) = \
        ::tirpol::cli::register_command(order, function)
