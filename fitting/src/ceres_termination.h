#pragma once
// Ceres' solver summary as the public SolverTermination.

#include <ceres/solver.h>

#include "tirpol/fitting/microfacet_fit.h"

namespace tirpol::fitting {

/// The summary's termination type (FAILURE for any Ceres adds later) and message.
SolverTermination termination_of(const ceres::Solver::Summary& summary);

}  // namespace tirpol::fitting
