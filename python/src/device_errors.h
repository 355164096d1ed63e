#pragma once
/// \file device_errors.h
/// Device failures (acquisition::DeviceError, returned as values by the drivers) become the Python
/// exception tirpol.DeviceError — a tirpol.Error whose `code` says which kind ("timeout",
/// "disconnected", ...) — at this application layer, as the CLI turns them into tirpol::Error.

#include <stdexcept>
#include <string>
#include <utility>

#include "tirpol/acquisition/result.h"

namespace tirpol::python {

struct DeviceFailure : std::runtime_error {
    DeviceFailure(const acquisition::DeviceError& e)
        : std::runtime_error(std::string(acquisition::to_string(e.code)) + ": " + e.message),
          code(acquisition::to_string(e.code)) {}
    std::string code;
};

template <typename T>
T value_or_raise(acquisition::Result<T>&& result) {
    if (!result.ok()) throw DeviceFailure(result.error());
    return std::move(result.value());
}

}  // namespace tirpol::python
