#pragma once
/// \file log.h
/// Logging through spdlog. Library code logs with spdlog's default logger; the CLI sets the level.

#include <spdlog/spdlog.h>

#include <string>

namespace tirpol {

/// Sets the global log level from "trace|debug|info|warn|error|off"; throws tirpol::Error
/// otherwise.
void set_log_level(const std::string& level);

}  // namespace tirpol
