#pragma once
/// \file device_uri.h
/// Device URIs, `scheme://target?key=value&key=value`: the parser the built-in camera factories use,
/// public so that a factory added with register_camera_scheme reads its URI with the same rules and
/// error messages.

#include <initializer_list>
#include <map>
#include <string>

namespace tirpol::acquisition {

struct DeviceUri {
    std::string text;    ///< the whole URI, for messages
    std::string scheme;  ///< "aravis", "v4l2", "sim", or a registered one
    std::string target;  ///< between "://" and "?"
    std::map<std::string, std::string> query;

    /// Throws tirpol::Error naming the URI for a key not in `allowed`.
    void check_keys(std::initializer_list<const char*> allowed) const;
    /// The query value parsed as a number; throws tirpol::Error naming the key if it does not parse.
    double number(const std::string& key, double fallback) const;
    int integer(const std::string& key, int fallback) const;
};

/// Splits a URI; throws tirpol::Error when there is no "://".
DeviceUri parse_device_uri(const std::string& uri);

}  // namespace tirpol::acquisition
