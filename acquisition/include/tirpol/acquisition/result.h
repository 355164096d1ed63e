#pragma once
/// \file result.h
/// Device drivers report expected failures (timeouts, bad replies, faults) as values, not
/// exceptions (STYLE.md "Errors"). The application layer turns them into tirpol::Error with
/// `value_or_throw`.

#include <string>
#include <utility>
#include <variant>

#include "tirpol/core/error.h"

namespace tirpol::acquisition {

enum class DeviceErrorCode {
    Timeout,          ///< the device did not answer in time
    BadReply,         ///< a reply that does not parse or does not match the request
    DeviceFault,      ///< the device answered with an error/fault status
    Disconnected,     ///< the port or connection went away
    NotSupported,     ///< the device lacks the feature
    InvalidArgument,  ///< the request was invalid (out of range, unknown feature)
    IoError,          ///< an operating-system I/O error
    Stopped,          ///< a motion ended early because Stage::stop() was called (e.g. on Ctrl-C)
};

const char* to_string(DeviceErrorCode code);

struct DeviceError {
    DeviceErrorCode code;
    std::string message;  ///< names the device and what happened
};

/// A value or a DeviceError.
template <typename T>
class Result {
public:
    Result(T value) : m_v(std::move(value)) {}            // NOLINT(google-explicit-constructor)
    Result(DeviceError error) : m_v(std::move(error)) {}  // NOLINT(google-explicit-constructor)
    bool ok() const { return std::holds_alternative<T>(m_v); }
    explicit operator bool() const { return ok(); }
    const T& value() const { return std::get<T>(m_v); }
    T& value() { return std::get<T>(m_v); }
    const DeviceError& error() const { return std::get<DeviceError>(m_v); }
    /// The value, or throws tirpol::Error "<code>: <message>".
    T value_or_throw() && {
        if (!ok()) throw Error(std::string(to_string(error().code)) + ": " + error().message);
        return std::get<T>(std::move(m_v));
    }

private:
    std::variant<T, DeviceError> m_v;
};

struct Done {};
using Status = Result<Done>;
inline Status ok_status() { return Done{}; }

}  // namespace tirpol::acquisition
