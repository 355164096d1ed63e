#pragma once
/// \file elliptec_stage.h
/// A Thorlabs Elliptec rotation mount (ELL14, ELL18) on a serial port at 9600 8N1
/// (elliptec:///dev/ttyUSB0?address=0). The scaling is read from the module's `IN` reply (pulses
/// over its travel), never assumed. Status codes of `GS` replies become DeviceErrors naming the
/// manual's meaning; `GS09` (busy) is waited out until the timeout.

#include <memory>

#include "tirpol/acquisition/internal/byte_port.h"
#include "tirpol/acquisition/stage.h"

namespace tirpol::acquisition {

struct ElliptecStageOptions {
    char address = '0';  ///< module address 0–F
    std::chrono::milliseconds reply_timeout{1000};
};

/// Asks the module for its information (`in`) and checks it is a rotary mount (travel 360°).
Result<std::unique_ptr<Stage>> open_elliptec_stage(std::unique_ptr<BytePort> port, std::string uri,
                                                   const ElliptecStageOptions& options = {});

}  // namespace tirpol::acquisition
