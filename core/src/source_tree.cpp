#include "tirpol/core/source_tree.h"

#include <vector>

#include "tirpol/core/error.h"

namespace tirpol {

std::filesystem::path find_config(const std::filesystem::path& relative) {
    std::vector<std::filesystem::path> starts = {std::filesystem::current_path()};
    std::error_code ec;
    const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) starts.push_back(exe.parent_path());
    for (auto dir : starts)
        for (; !dir.empty(); dir = dir.parent_path()) {
            const auto candidate = dir / "config" / relative;
            if (std::filesystem::exists(candidate)) return std::filesystem::absolute(candidate);
            if (dir == dir.parent_path()) break;
        }
    fail("cannot find config/{} in the working directory, beside the executable or above them "
         "(run from inside the tirpol source tree)",
         relative.string());
}

}  // namespace tirpol
