#include <unistd.h>

#include <cmath>
#include <string>

#include "tirpol/core/log.h"

namespace tirpol {

std::string format_duration(double seconds) {
    char buf[32];
    if (!std::isfinite(seconds) || seconds < 0) return "?";
    if (seconds >= 3600) {
        std::snprintf(buf, sizeof buf, "%dh%02dm", static_cast<int>(seconds / 3600),
                      static_cast<int>(std::fmod(seconds, 3600) / 60));
    } else if (seconds >= 60) {
        std::snprintf(buf, sizeof buf, "%dm%02ds", static_cast<int>(seconds / 60),
                      static_cast<int>(std::fmod(seconds, 60)));
    } else {
        std::snprintf(buf, sizeof buf, "%.1fs", seconds);
    }
    return buf;
}

ProgressReporter::ProgressReporter(std::string label, std::size_t total, std::FILE* stream,
                                   int interactive)
    : m_label(std::move(label)),
      m_total(total),
      m_stream(stream),
      m_interactive(interactive < 0 ? (stream && ::isatty(::fileno(stream))) : interactive != 0),
      m_start(std::chrono::steady_clock::now()),
      m_last_draw(m_start) {}

ProgressReporter::~ProgressReporter() { finish(); }

void ProgressReporter::advance(std::size_t n) {
    m_done += n;
    const auto now = std::chrono::steady_clock::now();
    // Redraw at most 10×/s on a terminal and every 10 s otherwise (so CI logs stay short).
    const auto min_gap =
        m_interactive ? std::chrono::milliseconds(100) : std::chrono::milliseconds(10000);
    std::unique_lock lock(m_mutex, std::try_to_lock);
    if (!lock.owns_lock() || now - m_last_draw < min_gap) return;
    m_last_draw = now;
    draw(false);
}

void ProgressReporter::finish() {
    std::lock_guard lock(m_mutex);
    if (m_finished) return;
    m_finished = true;
    draw(true);
}

void ProgressReporter::draw(bool final) {
    if (!m_stream) return;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
    const std::size_t done = std::min(m_done.load(), m_total);
    const double frac = m_total ? static_cast<double>(done) / static_cast<double>(m_total) : 1.0;
    const double eta = frac > 0 ? elapsed * (1.0 - frac) / frac : NAN;
    if (m_interactive) {
        constexpr int kWidth = 30;
        const int filled = static_cast<int>(frac * kWidth);
        std::string bar(static_cast<std::size_t>(filled), '#');
        bar.resize(kWidth, '.');
        std::fprintf(m_stream, "\r%s [%s] %5.1f%%  %s elapsed, ETA %s   ", m_label.c_str(),
                     bar.c_str(), 100.0 * frac, format_duration(elapsed).c_str(),
                     final ? "0.0s" : format_duration(eta).c_str());
        if (final) std::fputc('\n', m_stream);
    } else {
        std::fprintf(m_stream, "%s: %zu/%zu (%.0f%%), %s elapsed%s\n", m_label.c_str(), done,
                     m_total, 100.0 * frac, format_duration(elapsed).c_str(),
                     final ? "" : (", ETA " + format_duration(eta)).c_str());
    }
    std::fflush(m_stream);
}

}  // namespace tirpol
