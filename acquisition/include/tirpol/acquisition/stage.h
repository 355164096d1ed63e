#pragma once
/// \file stage.h
/// The rotation-stage interface (the mount that turns the wire-grid polarizer). Back ends: Thorlabs
/// APT (K10CR1 and other APT/Kinesis mounts) over a serial port or libusb, Thorlabs Elliptec
/// (ELL14), simulated. Opened by URI: `thorlabs-apt:///dev/ttyUSB0`, `thorlabs-apt+usb://<serial>`,
/// `elliptec:///dev/ttyUSB0?address=0`, `sim://`, or any scheme added with register_stage_scheme:
///   thorlabs-apt:///dev/ttyUSB0[?counts_per_degree=N&channel=1&address=0x50]   (serial port,
///   115200 8N1 RTS/CTS) thorlabs-apt+usb://<USB serial>[?...same keys] (libusb straight to the
///   FTDI chip) elliptec:///dev/ttyUSB0[?address=0]                                         (serial
///   port, 9600 8N1) sim://[?deg_per_s=V&start_deg=A&fail_on_move=N] (in-process simulation)
/// Common key: timeout_ms (reply timeout). Unknown schemes or keys give InvalidArgument naming
/// them. Angles in degrees, wrapped to [0, 360).

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

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
        return DeviceError{DeviceErrorCode::NotSupported,
                           info().uri + ": this stage has no stop command"};
    }
    /// Whether the home sensor is active now, read from the device. At counted zero it must be: a
    /// stage whose read-back is its own step counter (K10CR1) cannot otherwise see lost steps
    /// (docs/acquisition-stages.md, "Unkind stages"). Stages that do not report their home sensor
    /// return NotSupported.
    virtual Result<bool> home_sensor_active() {
        return DeviceError{DeviceErrorCode::NotSupported,
                           info().uri + ": this stage does not report its home sensor"};
    }
};

// Opening stages by URI.

/// Opens the stage a URI names, through the factory registered for its scheme; an unknown scheme is
/// InvalidArgument listing the registered ones.
Result<std::unique_ptr<Stage>> open_stage(const std::string& uri);

/// Makes the stage of a URI of its scheme (the whole URI is passed; parse it with split_device_uri,
/// device_uri.h).
using StageFactory = std::function<Result<std::unique_ptr<Stage>>(const std::string& uri)>;

/// Adds the factory for `scheme`, or replaces the registered one and returns it (empty if none), as
/// register_camera_scheme does for cameras. The built-in schemes above register this way.
/// Thread-safe.
StageFactory register_stage_scheme(const std::string& scheme, StageFactory factory);

/// The registered stage schemes, sorted.
std::vector<std::string> stage_schemes();

}  // namespace tirpol::acquisition
