#pragma once
// Runs the real `tirpol` executable (TIRPOL_CLI_PATH, set by apps/CMakeLists.txt) as a user would and
// returns its exit code and output, for the CLI tests in this folder (and tests/sweep, under mpirun).

#include <sys/wait.h>

#include <array>
#include <cstdio>
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

}  // namespace tirpol::test
