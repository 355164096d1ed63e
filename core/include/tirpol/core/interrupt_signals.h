#pragma once
/// \file interrupt_signals.h
/// Ctrl-C (SIGINT) and SIGTERM for programs that stop cleanly: while an InterruptSignals lives, the
/// first signal only sets a flag (a handler may do nothing else safely) that the program's loop or
/// a watcher thread reads; a second one ends the process at once with the signal's default action.
/// The previous handlers come back when it is destroyed.

#include <atomic>

namespace tirpol {

class InterruptSignals {
public:
    /// Installs the handlers and clears the flag. Throws tirpol::Error when another
    /// InterruptSignals is alive (there is one flag per process).
    InterruptSignals();
    /// Restores the handlers that were installed before.
    ~InterruptSignals();
    InterruptSignals(const InterruptSignals&) = delete;
    InterruptSignals& operator=(const InterruptSignals&) = delete;

    /// Set by the first SIGINT or SIGTERM.
    const std::atomic<bool>& flag() const;
    bool interrupted() const { return flag().load(); }

private:
    using Handler = void (*)(int);
    Handler m_previous_int, m_previous_term;
};

}  // namespace tirpol
