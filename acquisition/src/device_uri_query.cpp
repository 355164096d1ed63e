#include "device_uri_query.h"

#include <fmt/format.h>

#include <charconv>

namespace tirpol::acquisition::detail {

DeviceError bad_uri(const std::string& uri, const std::string& what) {
    return {DeviceErrorCode::InvalidArgument, fmt::format("{}: {}", uri, what)};
}

Result<double> uri_number(const std::string& uri, const DeviceUri& u, const std::string& key,
                          double fallback) {
    auto it = u.query.find(key);
    if (it == u.query.end()) return fallback;
    double v = 0;
    const auto* end = it->second.data() + it->second.size();
    const auto r = std::from_chars(it->second.data(), end, v);
    if (r.ec != std::errc() || r.ptr != end)
        return bad_uri(uri, fmt::format("{}={}: expected a number", key, it->second));
    return v;
}

Result<int> uri_integer(const std::string& uri, const DeviceUri& u, const std::string& key,
                        int fallback) {
    auto it = u.query.find(key);
    if (it == u.query.end()) return fallback;
    int v = 0;
    const std::string& s = it->second;
    const bool hex = s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X');
    const char* begin = s.data() + (hex ? 2 : 0);
    const auto r = std::from_chars(begin, s.data() + s.size(), v, hex ? 16 : 10);
    if (r.ec != std::errc() || r.ptr != s.data() + s.size())
        return bad_uri(uri, fmt::format("{}={}: expected an integer", key, s));
    return v;
}

Status check_uri_keys(const std::string& uri, const DeviceUri& u,
                      const std::set<std::string>& allowed) {
    for (const auto& [k, v] : u.query)
        if (!allowed.count(k)) {
            std::string list;
            for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
            return bad_uri(uri, fmt::format("unknown option '{}' (known: {})", k, list));
        }
    return ok_status();
}

}  // namespace tirpol::acquisition::detail
