#include <fstream>
#include <sstream>
#include <string>

#include "tirpol/core/error.h"
#include "tirpol/core/limits.h"

namespace tirpol {

std::optional<std::uint64_t> available_memory_bytes() {
    std::ifstream in("/proc/meminfo");
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("MemAvailable:", 0) != 0) continue;
        std::istringstream fields(line.substr(13));
        std::uint64_t kib = 0;
        std::string unit;
        if (fields >> kib >> unit && unit == "kB") return kib * 1024;
        return std::nullopt;
    }
    return std::nullopt;
}

void check_memory_estimate(std::uint64_t estimate_bytes, std::string_view what,
                           std::optional<std::uint64_t> available_bytes) {
    if (!available_bytes) return;
    const double budget = limits::kMaxMemoryFraction * static_cast<double>(*available_bytes);
    if (static_cast<double>(estimate_bytes) <= budget) return;
    constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;
    fail(
        "{}: needs an estimated {:.2f} GiB of memory, more than the {:.2f} GiB this machine has "
        "available "
        "({:.0f} % of MemAvailable, {:.2f} GiB); reduce the size or free memory",
        what, static_cast<double>(estimate_bytes) / kGiB, budget / kGiB,
        100.0 * limits::kMaxMemoryFraction, static_cast<double>(*available_bytes) / kGiB);
}

}  // namespace tirpol
