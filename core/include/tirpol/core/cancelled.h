#pragma once
/// \file cancelled.h
/// The exception a long computation throws when its caller's cancellation flag stops it early (the
/// Python module sets the flag on Ctrl-C): not bad input, so callers can tell it apart from an
/// Error.

#include <atomic>

#include "tirpol/core/error.h"

namespace tirpol {

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
