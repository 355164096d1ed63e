#pragma once
// The message of the tirpol::Error a call throws, for tests that check what a bad input is told.

#include <functional>
#include <string>

#include "tirpol/core/error.h"

namespace tirpol::test {

/// What `f` throws as tirpol::Error, or "(no error)" when it returns (a text no expected message
/// contains). Any other exception propagates and fails the test.
inline std::string error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

}  // namespace tirpol::test
