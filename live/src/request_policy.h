#pragma once
/// \file request_policy.h
/// Which HTTP requests the live view answers, decided from the request line and headers alone,
/// before a byte of the body is read (threat model: docs/live.md). Apart from the HTTP library so
/// that every rule is tested without a socket:
///  - Host must name this server (a loopback name, or for a wider bind an address or name of this
///    machine) with its port: a DNS-rebinding page reaches the server under the attacker's name.
///  - With a token (every non-loopback bind), no request without it.
///  - GET and HEAD carry no body; POST (every state change) needs `Content-Type: application/json`
///    (so no CORS "simple request" from another site can ever change state) and either an `Origin`
///    that is this server or the token in the query or the X-Tirpol-Token header (not the cookie,
///    which a browser attaches by itself); other methods, the CORS preflight included, are refused.
///  - A declared body larger than the limit is refused with 413 before it is read; a POST without
///    Content-Length or chunked encoding with 411.

#include <chrono>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/live/live_server.h"

namespace tirpol::live {

/// What the policy reads from a request (header values verbatim; absent headers empty).
struct RequestFacts {
    std::string method, host, origin, content_type, transfer_encoding;
    std::optional<std::string> content_length;  ///< absent: no Content-Length header
    bool explicit_token = false;                ///< the token in ?token= or X-Tirpol-Token
    bool cookie_token = false;                  ///< the token in the cookie set with the page
};

/// A refused request: the HTTP status and a message for the client.
struct Refusal {
    int status = 400;
    std::string message;
};

/// The `host:port` values a Host header may take for a server bound to `bind_address` on `port`:
/// localhost, 127.0.0.1 and [::1] always; for another address that address; for a wildcard bind
/// (0.0.0.0, ::) every address of this machine's interfaces and its host name (also as NAME.local).
std::vector<std::string> allowed_hosts(const std::string& bind_address, int port);

class RequestPolicy {
public:
    /// `token` empty: none required (loopback bind).
    RequestPolicy(std::vector<std::string> allowed_hosts, std::string token,
                  RequestLimits limits = {});

    /// Refusal of a request, or nullopt when it may be served (its body, if any, then read with at
    /// most limits().max_body_bytes).
    std::optional<Refusal> check(const RequestFacts& request) const;

    const RequestLimits& limits() const { return m_limits; }
    bool token_required() const { return !m_token.empty(); }
    /// Whether `host` (a Host header value) is one of allowed_hosts.
    bool host_allowed(const std::string& host) const;
    /// Whether `origin` is `http://` followed by an allowed host.
    bool origin_allowed(const std::string& origin) const;

private:
    std::vector<std::string> m_hosts;
    std::string m_token;
    RequestLimits m_limits;
};

}  // namespace tirpol::live
