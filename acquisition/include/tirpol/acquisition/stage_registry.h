#pragma once
/// \file stage_registry.h
/// Opens a rotation stage from a URI:
///   thorlabs-apt:///dev/ttyUSB0[?counts_per_degree=N&channel=1&address=0x50]   (serial port, 115200 8N1 RTS/CTS)
///   thorlabs-apt+usb://<USB serial>[?...same keys]                              (libusb straight to the FTDI chip)
///   elliptec:///dev/ttyUSB0[?address=0]                                         (serial port, 9600 8N1)
///   sim://[?deg_per_s=V&start_deg=A&fail_on_move=N]                             (in-process simulation)
/// Common key: timeout_ms (reply timeout). Unknown schemes or keys give InvalidArgument naming them.
/// More schemes plug in with register_stage_scheme.

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "tirpol/acquisition/stage.h"

namespace tirpol::acquisition {

/// A parsed device URI: scheme, the part after "://" up to '?', and the query keys.
struct StageUri {
    std::string scheme, path;
    std::map<std::string, std::string> query;
};
/// split_device_uri() (device_uri.h) with the target named `path`: InvalidArgument when there is no
/// "://" or a query item is not key=value.
Result<StageUri> parse_stage_uri(const std::string& uri);

/// Opens the stage a URI names, through the factory registered for its scheme; an unknown scheme is
/// InvalidArgument listing the registered ones.
Result<std::unique_ptr<Stage>> open_stage(const std::string& uri);

/// Makes the stage of a URI of its scheme (the whole URI is passed; parse it with parse_stage_uri).
using StageFactory = std::function<Result<std::unique_ptr<Stage>>(const std::string& uri)>;

/// Adds the factory for `scheme`, or replaces the registered one and returns it (empty if none), as
/// register_camera_scheme does for cameras. The built-in schemes above register this way. Thread-safe.
StageFactory register_stage_scheme(const std::string& scheme, StageFactory factory);

/// The registered stage schemes, sorted.
std::vector<std::string> stage_schemes();

}  // namespace tirpol::acquisition
