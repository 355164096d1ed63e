#pragma once
/// \file parameter_interval.h
/// The 2σ interval of a fitted parameter as every output reports it (CLI text and JSON, Python's
/// FitResult.intervals_2sigma): value ± 2σ intersected with the parameter's bounds, since the fit
/// never leaves them and values beyond them (n < 1.0 for a bound of 1.0) are not possible results.

#include <algorithm>

#include "tirpol/fitting/microfacet_fit.h"

namespace tirpol::fitting {

/// A closed interval [lower, upper] of a parameter's value.
struct ParameterInterval {
    double lower = 0.0;
    double upper = 0.0;
    bool clipped = false;  ///< value ± 2σ reached past a bound and was cut there
};

/// value ± 2σ of `p` clipped to [p.lower, p.upper]; for a fixed parameter, [value, value].
inline ParameterInterval interval_2sigma(const FittedParameter& p) {
    if (p.fixed) return {p.value, p.value, false};
    const double lo = p.value - 2.0 * p.std_uncertainty, hi = p.value + 2.0 * p.std_uncertainty;
    return {std::max(p.lower, lo), std::min(p.upper, hi), lo < p.lower || hi > p.upper};
}

}  // namespace tirpol::fitting
