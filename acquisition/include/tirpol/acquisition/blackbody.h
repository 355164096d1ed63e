#pragma once
/// \file blackbody.h
/// The blackbody-controller interface (the temperature-controlled source a radiometric calibration
/// looks at). Back end: the Fluke 4180/4181 Precision Infrared Calibrator's SCPI serial protocol
/// (fluke_scpi.h) over a serial port, and `sim://`, the same protocol served in-process by the
/// simulator (docs/acquisition-blackbody.md). Opened by URI with open_blackbody:
///   fluke-4180:///dev/ttyUSB0[?baud=9600&timeout_ms=1000]   Fluke 4180 (−15…120 °C) on a serial
///   port, 8N1 fluke-4181:///dev/ttyUSB0[?...]                          Fluke 4181 (35…500 °C)
///   sim://[?tau_s=60&ambient_k=296.15&noise_k=0.005&limit_k=0.05&window_s=30&model=4180&fault=none&fault_on_set=1]
///                       the same protocol served in-process by BlackbodySimulator
/// Unknown schemes or keys give InvalidArgument naming them.
/// Temperatures in kelvin; the device's °C stays inside the driver. Failures are values.

#include <memory>
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

/// The controller a URI names (see the file comment); InvalidArgument naming an unknown scheme or
/// key.
Result<std::unique_ptr<BlackbodyController>> open_blackbody(const std::string& uri);

}  // namespace tirpol::acquisition
