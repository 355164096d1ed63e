#pragma once
/// \file error.h
/// The one exception type of tirpol. Library code throws it for bad input (configs, files, device
/// replies turned into errors at the application layer); the CLI catches it once, prints the
/// message and exits non-zero. Messages name the file, the field and what was expected.

#include <fmt/format.h>

#include <stdexcept>
#include <string>

namespace tirpol {

class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Throws tirpol::Error with a fmt-formatted message.
template <typename... Args>
[[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) {
    throw Error(fmt::format(format, std::forward<Args>(args)...));
}

}  // namespace tirpol
