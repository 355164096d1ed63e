#pragma once
/// \file interruptible.h
/// Long C++ calls (a render, a capture) run on a worker thread with the GIL released while the
/// calling thread polls Python's signal handlers: Ctrl-C in a terminal or a notebook's "interrupt"
/// sets the call's cancellation flag, the C++ code stops at its next check, and KeyboardInterrupt
/// is raised once the worker has returned (nothing keeps running in the background).

#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <exception>
#include <future>
#include <utility>

namespace tirpol::python {

/// How often the waiting thread looks for a pending signal: short next to a human's patience,
/// long next to the cost of taking the GIL.
inline constexpr std::chrono::milliseconds kSignalPollPeriod{50};

/// Runs `work(cancel)` (which must not touch Python objects) and returns its result. Exceptions of
/// `work` propagate unchanged, except when a signal handler raised: then its exception
/// (KeyboardInterrupt) replaces whatever the stopped work threw. `on_interrupt` runs on the calling
/// thread right after `cancel` is set, for work blocked where no flag is read (a stage move: stop
/// it).
template <typename Work, typename OnInterrupt = void (*)()>
auto run_interruptible(
    Work&& work, OnInterrupt&& on_interrupt = [] {}) {
    std::atomic<bool> cancel{false};
    auto result = std::async(std::launch::async,
                             [&] { return work(static_cast<const std::atomic<bool>&>(cancel)); });
    for (;;) {
        bool done = false;
        {
            pybind11::gil_scoped_release release;
            done = result.wait_for(kSignalPollPeriod) == std::future_status::ready;
        }
        if (done) return result.get();
        if (PyErr_CheckSignals() != 0) {
            cancel = true;
            {
                pybind11::gil_scoped_release release;
                on_interrupt();
                result.wait();
            }
            try {
                result.get();
            } catch (
                const std::exception&) {  // the stopped work's Cancelled: the interrupt is the news
            }
            throw pybind11::error_already_set();
        }
    }
}

}  // namespace tirpol::python
