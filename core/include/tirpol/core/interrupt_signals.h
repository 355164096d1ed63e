#pragma once
/// \file interrupt_signals.h
/// Ctrl-C (SIGINT) and SIGTERM for programs that stop cleanly: while an InterruptSignals lives, the
/// first signal only sets a flag (a handler may do nothing else safely) that the program's loop or
/// a watcher thread reads; a second one ends the process at once with the signal's default action.
/// The previous handlers come back when it is destroyed.
///
/// The exception a long computation throws when its caller's cancellation flag stops it early (the
/// Python module sets the flag on Ctrl-C): not bad input, so callers can tell it apart from an
/// Error.

#include <atomic>
#include <chrono>
#include <functional>
#include <thread>

#include "tirpol/core/error.h"

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

/// What a program does when its interrupt flag rises while it may be blocked (in a device move, a
/// server loop): a signal handler can only set the flag, so a watcher thread polls it and, once it
/// is set, calls `on_interrupt`. Used by `tirpol acquire` (stop the stage) and `tirpol live` (stop
/// the server), so both leave through the same clean path.
class InterruptWatcher {
public:
    struct Options {
        /// After `on_interrupt` acted (returned true) it is called again after this period (a move
        /// that starts just after the first stop is stopped too); zero: once.
        std::chrono::milliseconds repeat_period{0};
        /// If the watcher still lives this long after the flag rose, `on_overdue` is called once
        /// and the watching ends (the program prints where it is and exits).
        std::chrono::milliseconds grace = std::chrono::milliseconds::max();
        std::function<void()> on_overdue;
    };

    /// `on_interrupt` returns whether it acted; while it returns false it is asked again at every
    /// poll (10 ms), e.g. until the device it stops exists.
    InterruptWatcher(const std::atomic<bool>& interrupt, std::function<bool()> on_interrupt,
                     Options options);
    /// Stops watching (joins the thread). Destroy it before what `on_interrupt` touches.
    ~InterruptWatcher();
    InterruptWatcher(const InterruptWatcher&) = delete;
    InterruptWatcher& operator=(const InterruptWatcher&) = delete;

private:
    void run();

    const std::atomic<bool>& m_interrupt;
    std::function<bool()> m_on_interrupt;
    Options m_options;
    std::atomic<bool> m_done{false};
    std::thread m_thread;
};

class Cancelled : public Error {
public:
    using Error::Error;
};

/// Throws Cancelled("<what> cancelled") when the flag `cancel` points to is set; null: never.
inline void throw_if_cancelled(const std::atomic<bool>* cancel, const char* what) {
    if (cancel && cancel->load(std::memory_order_relaxed))
        throw Cancelled(std::string(what) + " cancelled");
}

}  // namespace tirpol
