#pragma once
/// \file parameter_options.h
/// The micro-facet parameter settings as users write them (`tirpol fit --bound/--fix/--free`, the
/// Python module): NAME=LOWER:UPPER, NAME[=VALUE] and NAME, with NAME one of
/// microfacet_fit.h's parameter names (n, k, sigma, bias, tau_deg, omega_deg, rho_d, rho_v).

#include <array>
#include <string_view>

#include "tirpol/fitting/microfacet_fit.h"

namespace tirpol::fitting {

/// The settings of every parameter, in fit order.
using ParameterSettings = std::array<ParameterSetting, kMicrofacetParameterCount>;

/// Applies "NAME=LOWER:UPPER" (e.g. sigma=0.05:0.8) to that parameter's bounds. Throws
/// tirpol::Error naming `item` for another shape, an unknown name or a bound that is not a finite
/// number.
void apply_parameter_bound(std::string_view item, ParameterSettings& settings);

/// Applies "NAME" (hold at its initial value) or "NAME=VALUE" (hold at VALUE). Throws
/// tirpol::Error naming `item` for an unknown name or a value that is not a finite number.
void apply_parameter_fix(std::string_view item, ParameterSettings& settings);

/// Applies "NAME": the parameter is fitted. Throws tirpol::Error for an unknown name.
void apply_parameter_free(std::string_view name, ParameterSettings& settings);

}  // namespace tirpol::fitting
