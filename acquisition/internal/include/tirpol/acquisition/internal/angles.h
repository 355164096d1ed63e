#pragma once
/// \file angles.h
/// Angle helpers for rotation stages (degrees): core's, under acquisition's names.

#include "tirpol/core/stokes.h"

namespace tirpol::acquisition {

using ::tirpol::angle_difference_deg;
using ::tirpol::wrap_degrees;

}  // namespace tirpol::acquisition
