#pragma once
// The `tirpol` command line: one CLI11 app, one file per subcommand (each file defines a
// register_* function that adds its subcommand and the callback that runs it).

#include <CLI/CLI.hpp>

namespace tirpol::cli {

/// Exit codes (docs/cli.md): 0 success, 1 error in the input or a device, 2 bad command-line usage.
inline constexpr int kExitOk = 0;
inline constexpr int kExitError = 1;
inline constexpr int kExitUsage = 2;

int run(int argc, char** argv);

void register_info(CLI::App& app);
void register_planck(CLI::App& app);
void register_demo(CLI::App& app);

}  // namespace tirpol::cli
