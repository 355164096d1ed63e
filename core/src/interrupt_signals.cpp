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

}  // namespace tirpol
