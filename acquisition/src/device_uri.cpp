#include "tirpol/acquisition/device_uri.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "tirpol/core/error.h"

namespace tirpol::acquisition {

Result<DeviceUri> split_device_uri(const std::string& uri) {
    const auto invalid = [&](const std::string& what) {
        return DeviceError{DeviceErrorCode::InvalidArgument,
                           fmt::format("device URI '{}': {}", uri, what)};
    };
    DeviceUri out;
    out.text = uri;
    const auto sep = uri.find("://");
    if (sep == std::string::npos || sep == 0)
        return invalid("expected <scheme>://<target>[?key=value&...]");
    out.scheme = uri.substr(0, sep);
    const std::string rest = uri.substr(sep + 3);
    const auto q = rest.find('?');
    out.target = rest.substr(0, q);
    if (q == std::string::npos) return out;
    const std::string query = rest.substr(q + 1);
    for (std::size_t start = 0; start < query.size();) {
        const std::size_t end = std::min(query.find('&', start), query.size());
        const std::string pair = query.substr(start, end - start);
        start = end + 1;
        if (pair.empty()) continue;  // "a=1&&b=2" or a trailing '&': a harmless typo
        const auto eq = pair.find('=');
        if (eq == std::string::npos || eq == 0)
            return invalid(fmt::format("query item '{}' is not key=value", pair));
        out.query[pair.substr(0, eq)] = pair.substr(eq + 1);
    }
    return out;
}

DeviceUri parse_device_uri(const std::string& uri) {
    auto parsed = split_device_uri(uri);
    if (!parsed) throw Error(parsed.error().message);
    return std::move(parsed.value());
}

void DeviceUri::check_keys(std::initializer_list<const char*> allowed) const {
    for (const auto& entry : query) {
        // Not a structured binding: clang 14 (the fuzz build) cannot capture one in a lambda.
        const std::string& key = entry.first;
        if (std::none_of(allowed.begin(), allowed.end(), [&](const char* a) { return key == a; }))
            fail("device URI '{}': unknown query key '{}' (expected one of: {})", text, key,
                 fmt::join(std::vector<std::string>(allowed.begin(), allowed.end()), ", "));
    }
}

double DeviceUri::number(const std::string& key, double fallback) const {
    const auto it = query.find(key);
    if (it == query.end()) return fallback;
    char* end = nullptr;
    const double v = std::strtod(it->second.c_str(), &end);
    if (it->second.empty() || end != it->second.c_str() + it->second.size() || !std::isfinite(v))
        fail("device URI '{}': '{}={}' is not a number", text, key, it->second);
    return v;
}

int DeviceUri::integer(const std::string& key, int fallback) const {
    const auto it = query.find(key);
    if (it == query.end()) return fallback;
    int v = 0;
    const auto [ptr, ec] =
        std::from_chars(it->second.data(), it->second.data() + it->second.size(), v);
    if (ec != std::errc() || ptr != it->second.data() + it->second.size())
        fail("device URI '{}': '{}={}' is not an integer", text, key, it->second);
    return v;
}

}  // namespace tirpol::acquisition
