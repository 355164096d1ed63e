#pragma once
// The rule every Stage applies before an absolute move: a finite target, and homed first
// (stage.h: "homing before the first absolute move").

#include <fmt/format.h>

#include <cmath>

#include "tirpol/acquisition/result.h"

namespace tirpol::acquisition::detail {

/// ok_status() when the stage at `uri` may move to `angle_deg`, else an InvalidArgument error.
inline Status check_absolute_move(const std::string& uri, bool homed, double angle_deg) {
    if (!std::isfinite(angle_deg))
        return DeviceError{DeviceErrorCode::InvalidArgument,
                           fmt::format("{}: angle {} is not a number", uri, angle_deg)};
    if (!homed)
        return DeviceError{
            DeviceErrorCode::InvalidArgument,
            fmt::format("{}: not homed; home the stage before the first absolute move", uri)};
    return ok_status();
}

}  // namespace tirpol::acquisition::detail
