#include "api_request.h"

#include <charconv>

#include "access.h"
#include "tirpol/core/error.h"
#include "tirpol/core/utf8.h"

namespace tirpol::live {

namespace {
/// A request body quoted in an error: short, and valid UTF-8 (json parse errors quote raw bytes).
std::string excerpt(std::string_view text) {
    constexpr std::size_t kMaxQuoted = 80;
    return valid_utf8(text.substr(0, kMaxQuoted)) + (text.size() > kMaxQuoted ? "…" : "");
}
}  // namespace

std::uint64_t parse_after(const std::optional<std::string>& value) {
    if (!value) return 0;
    std::uint64_t after = 0;
    const char* end = value->data() + value->size();
    const auto r = std::from_chars(value->data(), end, after);
    if (value->empty() || r.ec != std::errc() || r.ptr != end)
        fail("after: expected a frame sequence number (decimal digits), got '{}'", excerpt(*value));
    return after;
}

RegionRequest parse_region_request(const std::optional<std::string>& x0,
                                   const std::optional<std::string>& y0,
                                   const std::optional<std::string>& x1,
                                   const std::optional<std::string>& y1,
                                   const std::optional<std::string>& dolp_min) {
    auto integer = [](const char* name, const std::optional<std::string>& value) {
        if (!value) fail("region: {} is required (a pixel coordinate)", name);
        int v = 0;
        const char* end = value->data() + value->size();
        const auto r = std::from_chars(value->data(), end, v);
        if (value->empty() || r.ec != std::errc() || r.ptr != end)
            fail("region: {} must be an integer pixel coordinate, got '{}'", name, excerpt(*value));
        return v;
    };
    RegionRequest request;
    request.region = {integer("x0", x0), integer("y0", y0), integer("x1", x1), integer("y1", y1)};
    if (dolp_min) {
        double v = 0.0;
        const char* end = dolp_min->data() + dolp_min->size();
        const auto r = std::from_chars(dolp_min->data(), end, v);
        if (dolp_min->empty() || r.ec != std::errc() || r.ptr != end || !(v >= 0.0 && v <= 1.0))
            fail("region: dolp_min must be a DoLP in [0, 1], got '{}'", excerpt(*dolp_min));
        request.dolp_min = v;
    }
    return request;
}

CaptureRequest parse_capture_request(std::string_view body) {
    const auto json = nlohmann::json::parse(body, nullptr, false);
    if (json.is_discarded() || !json.is_object())
        fail("capture request: expected a JSON object {{plan, output, resume}}, got '{}'",
             excerpt(body));
    for (const auto& [key, value] : json.items())
        if (key != "plan" && key != "output" && key != "resume")
            fail("capture request: unknown key '{}' (expected plan, output, resume)", excerpt(key));
    CaptureRequest request;
    for (const char* key : {"plan", "output"}) {
        const auto it = json.find(key);
        if (it == json.end() || !it->is_string() || it->get_ref<const std::string&>().empty())
            fail(
                "capture request: '{}' must be a non-empty string (a path on the machine running "
                "tirpol live)",
                key);
    }
    request.plan = json["plan"].get<std::string>();
    request.output = json["output"].get<std::string>();
    if (const auto it = json.find("resume"); it != json.end()) {
        if (!it->is_boolean()) fail("capture request: 'resume' must be true or false");
        request.resume = it->get<bool>();
    }
    return request;
}

nlohmann::json parse_observation(const std::optional<std::string>& client, std::string_view body) {
    if (!client || client->empty()) fail("observations: expected ?client=ID");
    auto json = nlohmann::json::parse(body, nullptr, false);
    if (json.is_discarded()) fail("observations: the body is not JSON: '{}'", excerpt(body));
    return json;
}

std::string cookie_value(std::string_view header, std::string_view name) {
    std::size_t at = 0;
    while (at < header.size()) {
        const std::size_t end = std::min(header.find(';', at), header.size());
        std::size_t start = at;
        while (start < end && header[start] == ' ') ++start;
        const std::string_view cookie = header.substr(start, end - start);
        if (cookie.size() > name.size() && cookie.substr(0, name.size()) == name &&
            cookie[name.size()] == '=')
            return std::string(cookie.substr(name.size() + 1));
        at = end + 1;
    }
    return "";
}

bool request_authorised(const std::string& token, const std::string& query_token,
                        const std::string& header_token, const std::string& cookie_header,
                        std::string_view cookie_name) {
    return token.empty() || token_matches(query_token, token) ||
           token_matches(header_token, token) ||
           token_matches(cookie_value(cookie_header, cookie_name), token);
}

std::string error_body(std::string_view message) {
    return json_text({{"error", std::string(message)}});
}

}  // namespace tirpol::live
