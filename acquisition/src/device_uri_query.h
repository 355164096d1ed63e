#pragma once
// Reading the query keys of a DeviceUri (device_uri.h) as values, shared by the stage and
// blackbody registries: every error names the URI and the key.

#include <set>
#include <string>

#include "tirpol/acquisition/device_uri.h"

namespace tirpol::acquisition::detail {

DeviceError bad_uri(const std::string& uri, const std::string& what);
/// The key's value as a number, `fallback` when absent; InvalidArgument naming the key otherwise.
Result<double> uri_number(const std::string& uri, const DeviceUri& u, const std::string& key,
                          double fallback);
/// ... as a decimal or 0x-prefixed hexadecimal integer.
Result<int> uri_integer(const std::string& uri, const DeviceUri& u, const std::string& key,
                        int fallback);
/// InvalidArgument naming the first key not in `allowed`, and listing the known ones.
Status check_uri_keys(const std::string& uri, const DeviceUri& u,
                      const std::set<std::string>& allowed);

}  // namespace tirpol::acquisition::detail
