#pragma once
/// \file log.h
/// Logging through spdlog. Library code logs with spdlog's default logger; the CLI sets the level.
///
/// A progress reporter for long jobs: a bar with ETA on a terminal, periodic plain lines otherwise
/// (logs, CI). Thread-safe `advance`.

#include <spdlog/spdlog.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <string>

namespace tirpol {

/// Sets the global log level from "trace|debug|info|warn|error|off"; throws tirpol::Error
/// otherwise.
void set_log_level(const std::string& level);

class ProgressReporter {
public:
    /// `stream` defaults to stderr; `interactive` defaults to isatty(stream).
    ProgressReporter(std::string label, std::size_t total, std::FILE* stream = stderr,
                     int interactive = -1);
    ~ProgressReporter();

    void advance(std::size_t n = 1);
    void finish();
    std::size_t done() const { return m_done.load(); }

private:
    void draw(bool final);

    std::string m_label;
    std::size_t m_total;
    std::FILE* m_stream;
    bool m_interactive;
    std::atomic<std::size_t> m_done{0};
    std::mutex m_mutex;
    std::chrono::steady_clock::time_point m_start;
    std::chrono::steady_clock::time_point m_last_draw;
    bool m_finished = false;
};

/// Formats seconds as "1h02m", "3m05s" or "12.3s".
std::string format_duration(double seconds);

}  // namespace tirpol
