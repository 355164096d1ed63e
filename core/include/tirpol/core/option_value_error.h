#pragma once
/// \file option_value_error.h
/// A value a user gave for a command-line option that the library found wrong once it had read the
/// files the value refers to (a time in a site's offset, a name in a file's list). The CLI exits
/// 2 with it, as a usage error naming the option, instead of 1 for a bad input file.

#include <string>

#include "tirpol/core/error.h"

namespace tirpol {

class OptionValueError : public Error {
public:
    /// `message` may begin with `option` already; the CLI then prints it once.
    OptionValueError(std::string option, const std::string& message)
        : Error(message), m_option(std::move(option)) {}
    /// The option ("--at").
    const std::string& option() const { return m_option; }

private:
    std::string m_option;
};

}  // namespace tirpol
