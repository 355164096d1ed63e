#pragma once
/// \file device_uri.h
/// Device URIs, `scheme://target?key=value&key=value`: the one parser the built-in camera, stage
/// and blackbody factories use, public so that a factory added with register_camera_scheme or
/// register_stage_scheme reads its URI with the same rules and error messages.

#include <initializer_list>
#include <map>
#include <string>

#include "tirpol/acquisition/result.h"

namespace tirpol::acquisition {

struct DeviceUri {
    std::string text;    ///< the whole URI, for messages
    std::string scheme;  ///< "aravis", "v4l2", "sim", or a registered one
    std::string target;  ///< between "://" and "?"
    std::map<std::string, std::string> query;

    /// Throws tirpol::Error naming the URI for a key not in `allowed`.
    void check_keys(std::initializer_list<const char*> allowed) const;
    /// The query value parsed as a number; throws tirpol::Error naming the key if it does not
    /// parse.
    double number(const std::string& key, double fallback) const;
    int integer(const std::string& key, int fallback) const;
};

/// Splits a URI, the one parser of device URIs (cameras, stages, blackbodies): InvalidArgument
/// naming the URI when there is no "://" or a query item is not key=value. Empty query items
/// ("a=1&&b=2", a trailing '&') are skipped.
Result<DeviceUri> split_device_uri(const std::string& uri);

/// split_device_uri() for camera factories, which throw: tirpol::Error with the same message.
DeviceUri parse_device_uri(const std::string& uri);

}  // namespace tirpol::acquisition
