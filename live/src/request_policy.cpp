#include "request_policy.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>

#include "access.h"
#include "tirpol/core/utf8.h"

namespace tirpol::live {

namespace {
std::string lower(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return text;
}

std::string trim(const std::string& text) {
    const auto first = text.find_first_not_of(" \t");
    if (first == std::string::npos) return "";
    return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

/// A header value quoted in a refusal: short and valid UTF-8.
std::string quoted(const std::string& value) {
    constexpr std::size_t kMaxQuoted = 80;
    return valid_utf8(std::string_view(value).substr(0, kMaxQuoted)) +
           (value.size() > kMaxQuoted ? "…" : "");
}

bool is_wildcard(const std::string& address) {
    return address == "0.0.0.0" || address == "::" || address.empty();
}

std::string with_port(const std::string& host, int port) {
    const std::string name =
        host.find(':') != std::string::npos && host.front() != '[' ? "[" + host + "]" : host;
    return lower(name) + ":" + std::to_string(port);
}
}  // namespace

std::vector<std::string> allowed_hosts(const std::string& bind_address, int port) {
    std::vector<std::string> names{"localhost", "127.0.0.1", "::1"};
    if (is_wildcard(bind_address)) {
        for (const std::string& a : interface_addresses()) names.push_back(a);
        if (const std::string name = host_name(); !name.empty()) {
            names.push_back(name);
            names.push_back(name + ".local");
        }
    } else {
        names.push_back(bind_address);
    }
    std::vector<std::string> hosts;
    for (const std::string& name : names) {
        hosts.push_back(with_port(name, port));
        if (port == 80)
            hosts.push_back(lower(name.find(':') != std::string::npos ? "[" + name + "]" : name));
    }
    std::sort(hosts.begin(), hosts.end());
    hosts.erase(std::unique(hosts.begin(), hosts.end()), hosts.end());
    return hosts;
}

RequestPolicy::RequestPolicy(std::vector<std::string> allowed_hosts, std::string token,
                             RequestLimits limits)
    : m_hosts(std::move(allowed_hosts)), m_token(std::move(token)), m_limits(limits) {}

bool RequestPolicy::host_allowed(const std::string& host) const {
    return std::find(m_hosts.begin(), m_hosts.end(), lower(trim(host))) != m_hosts.end();
}

bool RequestPolicy::origin_allowed(const std::string& origin) const {
    const std::string o = lower(trim(origin));
    const std::string scheme = "http://";
    return o.rfind(scheme, 0) == 0 && host_allowed(o.substr(scheme.size()));
}

std::optional<Refusal> RequestPolicy::check(const RequestFacts& r) const {
    if (!host_allowed(r.host))
        return Refusal{
            403,
            fmt::format("Host '{}' is not an address of this live view (a page reaching it under "
                        "another name, as DNS rebinding does, is refused)",
                        quoted(r.host))};
    if (token_required() && !r.explicit_token && !r.cookie_token)
        return Refusal{401,
                       "tirpol live: this page needs the access token printed when the server "
                       "started (?token=...)"};

    std::optional<std::uint64_t> length;
    if (r.content_length) {
        std::uint64_t n = 0;
        const std::string& v = *r.content_length;
        const auto parsed = std::from_chars(v.data(), v.data() + v.size(), n);
        if (v.empty() || parsed.ec != std::errc() || parsed.ptr != v.data() + v.size())
            return Refusal{400, fmt::format("Content-Length '{}' is not a byte count", quoted(v))};
        length = n;
    }
    const std::string encoding = lower(trim(r.transfer_encoding));
    if (!encoding.empty() && encoding != "chunked")
        return Refusal{501, fmt::format("Transfer-Encoding '{}' is not supported (only chunked)",
                                        quoted(encoding))};
    const bool has_body = (length && *length > 0) || encoding == "chunked";

    if (r.method == "GET" || r.method == "HEAD") {
        if (has_body) return Refusal{400, fmt::format("a {} request carries no body", r.method)};
        return std::nullopt;
    }
    if (r.method != "POST")
        return Refusal{
            405,
            fmt::format("method {} is not served (GET, HEAD, POST only; no cross-origin requests)",
                        quoted(r.method))};

    const std::string content_type =
        lower(trim(r.content_type.substr(0, r.content_type.find(';'))));
    if (content_type != "application/json")
        return Refusal{415, fmt::format("a POST must be 'Content-Type: application/json', got '{}'",
                                        quoted(r.content_type))};
    if (!r.explicit_token && !origin_allowed(r.origin))
        return Refusal{
            403,
            r.origin.empty()
                ? std::string(
                      "a POST needs the header 'Origin: http://HOST:PORT' of this live view "
                      "(browsers send it; scripts must add it)")
                : fmt::format("Origin '{}' is not this live view: requests from other sites are "
                              "refused",
                              quoted(r.origin))};
    if (!length && encoding != "chunked")
        return Refusal{411, "a POST needs a Content-Length (or chunked encoding)"};
    if (length && *length > m_limits.max_body_bytes)
        return Refusal{413, fmt::format("request body of {} bytes exceeds the limit of {} bytes",
                                        *length, m_limits.max_body_bytes)};
    return std::nullopt;
}

}  // namespace tirpol::live
