#pragma once
// Where an executable is on PATH, for tests that run one (chromium, the fake GigE Vision camera).

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>

namespace tirpol::test {

/// The first `name` on PATH that this process may execute, or nullopt.
inline std::optional<std::filesystem::path> find_on_path(const std::string& name) {
    std::stringstream dirs(std::getenv("PATH") ? std::getenv("PATH") : "/usr/bin:/bin");
    for (std::string dir; std::getline(dirs, dir, ':');)
        if (::access((std::filesystem::path(dir) / name).c_str(), X_OK) == 0)
            return std::filesystem::path(dir) / name;
    return std::nullopt;
}

}  // namespace tirpol::test
