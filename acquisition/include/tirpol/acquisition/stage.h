#pragma once
/// \file stage.h
/// The rotation-stage interface (the mount that turns the wire-grid polarizer). Back ends: Thorlabs
/// APT (K10CR1 and other APT/Kinesis mounts) over a serial port or libusb, Thorlabs Elliptec (ELL14),
/// simulated. Opened by URI: `thorlabs-apt:///dev/ttyUSB0`, `thorlabs-apt+usb://<serial>`,
/// `elliptec:///dev/ttyUSB0?address=0`, `sim://` (see open_stage in stage_registry.h).
/// Angles in degrees, wrapped to [0, 360).

#include <chrono>
#include <string>

#include "tirpol/acquisition/result.h"

namespace tirpol::acquisition {

struct StageInfo {
    std::string uri;
    std::string vendor, model, serial, firmware;
    double counts_per_degree = 0.0;  ///< read from the device where it reports it
};

class Stage {
public:
    virtual ~Stage() = default;
    virtual StageInfo info() const = 0;
    virtual Status home(std::chrono::milliseconds timeout) = 0;
    virtual bool is_homed() const = 0;
    /// Moves to `angle_deg` (wrapped) and waits until the move completes or `timeout` passes.
    virtual Status move_absolute(double angle_deg, std::chrono::milliseconds timeout) = 0;
    /// Current angle in degrees, read back from the device.
    virtual Result<double> position_deg() = 0;
    /// Tells the device to stop moving now (APT MGMSG_MOT_MOVE_STOP, Elliptec `st`). Safe to call
    /// from another thread while home() or move_absolute() waits: that call then returns promptly
    /// with DeviceErrorCode::Stopped and the stage stays where it stopped (not homed if homing was
    /// cut short). When nothing moves it sends nothing and returns ok. Stages that cannot stop
    /// return NotSupported.
    virtual Status stop() {
        return DeviceError{DeviceErrorCode::NotSupported, info().uri + ": this stage has no stop command"};
    }
};

}  // namespace tirpol::acquisition
