#include "tirpol/core/interrupt_signals.h"

#include <csignal>

#include "tirpol/core/error.h"

namespace tirpol {

namespace {
std::atomic<bool> g_interrupted{false};
std::atomic<bool> g_installed{false};

extern "C" void on_interrupt_signal(int sig) {
    if (g_interrupted.exchange(true)) {
        std::signal(sig, SIG_DFL);
        std::raise(sig);
    }
}
}  // namespace

InterruptSignals::InterruptSignals() {
    if (g_installed.exchange(true))
        fail("InterruptSignals: another one is alive; the process has one interrupt flag");
    g_interrupted = false;
    m_previous_int = std::signal(SIGINT, on_interrupt_signal);
    m_previous_term = std::signal(SIGTERM, on_interrupt_signal);
}

InterruptSignals::~InterruptSignals() {
    std::signal(SIGINT, m_previous_int);
    std::signal(SIGTERM, m_previous_term);
    g_installed = false;
}

const std::atomic<bool>& InterruptSignals::flag() const { return g_interrupted; }

InterruptWatcher::InterruptWatcher(const std::atomic<bool>& interrupt,
                                   std::function<bool()> on_interrupt, Options options)
    : m_interrupt(interrupt),
      m_on_interrupt(std::move(on_interrupt)),
      m_options(std::move(options)),
      m_thread([this] { run(); }) {}

InterruptWatcher::~InterruptWatcher() {
    m_done = true;
    m_thread.join();
}

void InterruptWatcher::run() {
    using Clock = std::chrono::steady_clock;
    constexpr auto kPoll = std::chrono::milliseconds(10);
    while (!m_done && !m_interrupt) std::this_thread::sleep_for(kPoll);
    if (m_done) return;
    const auto risen_at = Clock::now();
    auto next_call = risen_at;
    bool called_once = false;
    while (!m_done) {
        const auto now = Clock::now();
        if (std::chrono::duration_cast<std::chrono::milliseconds>(now - risen_at) >=
            m_options.grace) {
            if (m_options.on_overdue) m_options.on_overdue();
            return;
        }
        const bool may_call = !called_once || m_options.repeat_period.count() > 0;
        if (may_call && now >= next_call && m_on_interrupt()) {
            called_once = true;
            next_call = now + m_options.repeat_period;
        }
        std::this_thread::sleep_for(kPoll);
    }
}

}  // namespace tirpol
