#pragma once
/// \file temperature_value.h
/// Temperatures as written in scene files: a number is kelvin; a string may carry its unit,
/// "288.15 K" or "15 °C" (ARCHITECTURE.md: °C accepted in configs only where written as such).

#include "tirpol/core/config.h"

namespace tirpol::simulation {

/// The temperature of a scalar config node in kelvin; error (file:line:field) for anything else or
/// for a value at or below 0 K.
double temperature_k_from_config(const ConfigNode& node);

}  // namespace tirpol::simulation
