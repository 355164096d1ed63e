#pragma once
/// \file api_request.h
/// What the live view's HTTP API reads from a request, apart from the HTTP library (live_server.cpp
/// passes it the decoded query values, headers and body): the pieces a page or anyone on the
/// network controls, checked here so that they can be tested and fuzzed without a socket
/// (fuzz/targets/live_request.cpp). Every rejection is a tirpol::Error whose message the server
/// returns as a 400 JSON body.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "capture_control.h"
#include "region_statistics.h"

namespace tirpol::live {

/// `?after=SEQ`: a decimal sequence number (digits only, fits 64 bits); absent = 0. Throws
/// otherwise, since "-1" or "1e9" would silently mean "wait for a frame that never comes".
std::uint64_t parse_after(const std::optional<std::string>& value);

/// The query of GET /api/region: `x0`, `y0`, `x1`, `y1` (decimal integers, corners included, all
/// required) and `dolp_min` (a number in [0, 1]; absent = 0). Throws naming the parameter.
struct RegionRequest {
    PixelRegion region;
    double dolp_min = 0.0;
};
RegionRequest parse_region_request(const std::optional<std::string>& x0,
                                   const std::optional<std::string>& y0,
                                   const std::optional<std::string>& x1,
                                   const std::optional<std::string>& y1,
                                   const std::optional<std::string>& dolp_min);

/// The body of POST /api/capture/start: a JSON object {plan: string, output: string, resume: bool?}
/// with no other keys.
CaptureRequest parse_capture_request(std::string_view body);

/// The body of POST /api/observations?client=ID: any JSON value; `client` must be non-empty.
nlohmann::json parse_observation(const std::optional<std::string>& client, std::string_view body);

/// The value of cookie `name` in a Cookie header ("a=1; b=2"), or "".
std::string cookie_value(std::string_view header, std::string_view name);

/// Whether a request may pass when `token` is required (access.h): the `?token=` query value, the
/// X-Tirpol-Token header or the cookie `cookie_name` in the Cookie header must equal it. An empty
/// `token` (loopback) lets every request pass.
bool request_authorised(const std::string& token, const std::string& query_token,
                        const std::string& header_token, const std::string& cookie_header,
                        std::string_view cookie_name);

/// {"error": message} as JSON text, valid UTF-8 whatever bytes the message quotes from the request.
std::string error_body(std::string_view message);

}  // namespace tirpol::live
