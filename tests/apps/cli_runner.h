#pragma once
// Runs the real `tirpol` executable (TIRPOL_CLI_PATH, set by apps/CMakeLists.txt) as a user would
// and returns its exit code and output, for the CLI tests in this folder (and tests/sweep, under
// mpirun).

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <set>
#include <sstream>
#include <string>

namespace tirpol::test {

struct CliRun {
    int exit_code;
    std::string out;  ///< stdout, followed by stderr unless merge_stderr is false
};

/// Runs a shell command line; stderr is merged into the output unless `merge_stderr` is false.
inline CliRun run_command(const std::string& command, bool merge_stderr = true) {
    const std::string cmd = command + (merge_stderr ? " 2>&1" : " 2>/dev/null");
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return {-1, "popen failed"};
    std::string out;
    std::array<char, 4096> buf{};
    std::size_t n;
    while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) out.append(buf.data(), n);
    const int status = pclose(pipe);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

inline CliRun run_cli(const std::string& args, bool merge_stderr = true) {
    return run_command(std::string(TIRPOL_CLI_PATH) + " " + args, merge_stderr);
}

/// The names under "Subcommands:" in `tirpol [PATH] --help` (PATH "calibrate" lists its nested
/// ones).
inline std::set<std::string> subcommands_in_help(const std::string& path) {
    const CliRun help = run_cli(path + " --help", false);
    std::set<std::string> names;
    std::istringstream lines(help.out);
    bool listing = false;
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind("Subcommands:", 0) == 0)
            listing = true;
        else if (listing && line.rfind("  ", 0) == 0) {
            std::istringstream words(line);
            std::string name;
            words >> name;
            names.insert(path.empty() ? name : path + " " + name);
        } else if (listing && !line.empty())
            listing = false;
    }
    return names;
}

}  // namespace tirpol::test
