#pragma once
// What this run of `tirpol` is, for the provenance of the files it writes.

#include <string>

namespace tirpol::cli {

/// "tirpol X.Y.Z" (the CMake project version).
std::string version_text();

/// The command line of this run, shell-quoted so it pastes back.
const std::string& command_line_text();

}  // namespace tirpol::cli
