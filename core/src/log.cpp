#include "tirpol/core/log.h"

#include "tirpol/core/error.h"

namespace tirpol {

void set_log_level(const std::string& level) {
    const auto parsed = spdlog::level::from_str(level);
    if (parsed == spdlog::level::off && level != "off")
        fail("unknown log level '{}' (expected trace, debug, info, warn, error or off)", level);
    spdlog::set_level(parsed);
}

}  // namespace tirpol
