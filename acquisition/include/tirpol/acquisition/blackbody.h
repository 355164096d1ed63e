#pragma once
/// \file blackbody.h
/// The blackbody-controller interface (the temperature-controlled source a radiometric calibration
/// looks at). Back end: the Fluke 4180/4181 Precision Infrared Calibrator's SCPI serial protocol
/// (fluke_scpi.h) over a serial port, and `sim://`, the same protocol served in-process by the
/// simulator (docs/acquisition-blackbody.md). Opened by URI (open_blackbody in blackbody_registry.h).
/// Temperatures in kelvin; the device's °C stays inside the driver. Failures are values.

#include <string>

#include "tirpol/acquisition/result.h"

namespace tirpol::acquisition {

struct BlackbodyInfo {
    std::string uri;
    std::string vendor, model, serial, firmware;          ///< from *IDN?
    double min_set_point_k = 0.0, max_set_point_k = 0.0;  ///< the model's set-point range
};

/// One poll of the controller.
struct BlackbodyStatus {
    double temperature_k = 0.0;  ///< the control sensor's temperature now
    double set_point_k = 0.0;    ///< the set-point the controller holds
    bool stable = false;         ///< the controller's own stability flag (its STABLE LIMIT test)
};

class BlackbodyController {
public:
    virtual ~BlackbodyController() = default;
    virtual BlackbodyInfo info() const = 0;
    /// Sends the set-point and checks the controller accepted it (error queue and read-back).
    /// InvalidArgument outside [min_set_point_k, max_set_point_k] (nothing is sent).
    virtual Status set_temperature_k(double set_point_k) = 0;
    /// Temperature, set-point and stability flag. DeviceFault when the over-temperature cutout has
    /// tripped (the heater is off), Timeout when it does not answer, BadReply for a garbled reply.
    virtual Result<BlackbodyStatus> status() = 0;
};

}  // namespace tirpol::acquisition
