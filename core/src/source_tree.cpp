#include "tirpol/core/source_tree.h"

#include <dlfcn.h>

#include <string>
#include <vector>

#include "tirpol/core/error.h"

// Set by core/CMakeLists.txt for this file only: where `cmake --install` puts config/, relative to
// the install prefix and as the absolute path of the configured prefix.
#ifndef TIRPOL_CONFIG_INSTALL_RELATIVE
#define TIRPOL_CONFIG_INSTALL_RELATIVE "share/tirpol/config"
#endif
#ifndef TIRPOL_CONFIG_INSTALL_DIR
#define TIRPOL_CONFIG_INSTALL_DIR ""
#endif

namespace tirpol {
namespace {

/// The file this code was loaded from: the executable, or the Python extension module that linked
/// core.
std::filesystem::path loaded_binary() {
    Dl_info info{};
    if (dladdr(reinterpret_cast<const void*>(&find_config), &info) == 0 ||
        info.dli_fname == nullptr)
        return {};
    std::error_code ec;
    auto path = std::filesystem::canonical(info.dli_fname, ec);
    return ec ? std::filesystem::path{} : path;
}

}  // namespace

std::filesystem::path find_config(const std::filesystem::path& relative) {
    std::vector<std::filesystem::path> candidates;
    // The source tree: config/ in the working directory or a parent, then beside the executable or
    // above.
    std::vector<std::filesystem::path> starts = {std::filesystem::current_path()};
    std::error_code ec;
    const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) starts.push_back(exe.parent_path());
    for (auto dir : starts)
        for (; !dir.empty(); dir = dir.parent_path()) {
            candidates.push_back(dir / "config" / relative);
            if (dir == dir.parent_path()) break;
        }
    // An installed tree, wherever its prefix was moved: <prefix>/share/tirpol/config above the
    // installed executable (<prefix>/bin) or Python extension
    // (<prefix>/lib/python3.X/dist-packages/tirpol).
    std::vector<std::filesystem::path> binaries;
    if (!ec) binaries.push_back(exe);
    if (auto binary = loaded_binary(); !binary.empty()) binaries.push_back(binary);
    for (const auto& binary : binaries)
        for (auto dir = binary.parent_path(); !dir.empty(); dir = dir.parent_path()) {
            candidates.push_back(dir / TIRPOL_CONFIG_INSTALL_RELATIVE / relative);
            if (dir == dir.parent_path()) break;
        }
    // The prefix configured at build time.
    if (const std::string installed = TIRPOL_CONFIG_INSTALL_DIR; !installed.empty())
        candidates.push_back(std::filesystem::path(installed) / relative);
    for (const auto& candidate : candidates)
        if (std::filesystem::exists(candidate, ec)) return std::filesystem::absolute(candidate);
    fail(
        "cannot find config/{} in the working directory, beside the executable or above them (run "
        "from inside "
        "the tirpol source tree), nor an installed {}/{} above the program or at '{}'",
        relative.string(), TIRPOL_CONFIG_INSTALL_RELATIVE, relative.string(),
        TIRPOL_CONFIG_INSTALL_DIR);
}

}  // namespace tirpol
