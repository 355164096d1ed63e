#pragma once
/// \file checks.h
/// Range checks shared by every reader and command, so that one quantity is held to one range
/// (limits.h) with one wording. Each throws tirpol::Error naming `what` (a field, flag or column).

#include <string_view>

namespace tirpol {

/// `temperature_k` if it lies in [limits::kMinTemperatureK, limits::kMaxTemperatureK].
double check_temperature_k(double temperature_k, std::string_view what);

/// `value` if it is finite: a computed result that overflowed is an error, never printed as
/// inf/nan.
double check_finite(double value, std::string_view what);

/// `value` if it is finite and ≥ 0 (an uncertainty, a noise level, a duration).
double check_non_negative(double value, std::string_view what);

}  // namespace tirpol
