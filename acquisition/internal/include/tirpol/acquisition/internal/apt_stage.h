#pragma once
/// \file apt_stage.h
/// A Thorlabs APT rotation mount (K10CR1 and other single-channel APT/Kinesis stepper mounts) over
/// any byte port: a serial port (thorlabs-apt:///dev/ttyUSB0) or libusb to the FTDI chip
/// (thorlabs-apt+usb://<serial>). Message flow per the APT protocol document:
/// HW_NO_FLASH_PROGRAMMING, HW_REQ_INFO → HW_GET_INFO, MOD_SET_CHANENABLESTATE,
/// MOT_REQ_USTATUSUPDATE → GET_USTATUSUPDATE (the homed bit survives across host sessions),
/// MOT_MOVE_HOME → MOT_MOVE_HOMED, MOT_MOVE_ABSOLUTE → MOT_MOVE_COMPLETED (or MOT_MOVE_STOPPED),
/// HW_RICHRESPONSE = device error.

#include <memory>

#include "tirpol/acquisition/internal/apt_protocol.h"
#include "tirpol/acquisition/internal/byte_port.h"
#include "tirpol/acquisition/stage.h"

namespace tirpol::acquisition {

struct AptStageOptions {
    double counts_per_degree =
        apt::kK10cr1CountsPerDegree;  ///< APT replies carry no scaling: per model
    std::uint8_t address = apt::kUsbDeviceAddress;
    std::uint8_t channel = 1;
    std::chrono::milliseconds reply_timeout{
        1000};  ///< for requests answered at once (info, status)
};

/// Identifies the controller and reads its status. Timeout if it does not answer HW_REQ_INFO.
Result<std::unique_ptr<Stage>> open_apt_stage(std::unique_ptr<BytePort> port, std::string uri,
                                              const AptStageOptions& options = {});

}  // namespace tirpol::acquisition
