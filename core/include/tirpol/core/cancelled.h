#pragma once
/// \file cancelled.h
/// The exception a long computation throws when its caller's cancellation flag stops it early (the
/// Python module sets the flag on Ctrl-C): not bad input, so callers can tell it apart from an Error.

#include "tirpol/core/error.h"

namespace tirpol {

class Cancelled : public Error {
public:
    using Error::Error;
};

}  // namespace tirpol
