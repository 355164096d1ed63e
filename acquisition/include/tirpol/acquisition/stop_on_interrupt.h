#pragma once
/// \file stop_on_interrupt.h
/// What Ctrl-C (SIGINT/SIGTERM) does during `tirpol acquire`: a signal handler can only set a flag,
/// and the capture loop may be blocked in a move, a homing or a device call. A watcher thread turns
/// the flag into Stage::stop() (repeated every `restop_period`, so a move that starts just after
/// the first stop is stopped too) and, if the program has still not finished `grace` after the
/// signal, calls `on_overdue` (the CLI prints where the session is and exits: every session write
/// is atomic, so nothing recorded is lost).

#include <atomic>
#include <chrono>
#include <functional>

#include "tirpol/acquisition/stage.h"
#include "tirpol/core/interrupt_signals.h"

namespace tirpol::acquisition {

class StopOnInterrupt {
public:
    StopOnInterrupt(const std::atomic<bool>& interrupt, std::chrono::milliseconds grace,
                    std::function<void()> on_overdue,
                    std::chrono::milliseconds restop_period = std::chrono::milliseconds(250));
    /// Stops watching (joins the thread). Destroy it before the stage it watches.
    ~StopOnInterrupt();
    StopOnInterrupt(const StopOnInterrupt&) = delete;
    StopOnInterrupt& operator=(const StopOnInterrupt&) = delete;

    /// The stage to stop from now on (nullptr: none yet).
    void watch(Stage* stage) { m_stage = stage; }
    /// How many stop commands were sent (for tests and the log).
    int stops_sent() const { return m_stops_sent; }

private:
    bool stop_stage();

    std::atomic<Stage*> m_stage{nullptr};
    std::atomic<int> m_stops_sent{0};
    InterruptWatcher m_watcher;  // last: it stops watching before the members above go
};

}  // namespace tirpol::acquisition
