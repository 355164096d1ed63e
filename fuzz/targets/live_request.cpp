// Fuzz target: what the live view's HTTP API reads from a request (live/api_request.h), without a
// socket. The input is split at its first three newlines into the ?after= value, the Cookie header
// and the ?client= value (as cpp-httplib hands them over, already URL-decoded); the rest is the
// POST body, read both as a capture request and as an observation. Every error message must come
// out as valid JSON text.
#include <string>

#include "api_request.h"
#include "fuzz_support.h"
#include "tirpol/core/utf8.h"

namespace live = tirpol::live;

namespace {
std::string take_line(std::string_view& rest) {
    const auto nl = rest.find('\n');
    const std::string line(rest.substr(0, nl));
    rest.remove_prefix(nl == std::string_view::npos ? rest.size() : nl + 1);
    return line;
}

template <typename F>
void parse_or_answer_400(F&& parse) {
    try {
        parse();
    } catch (const tirpol::Error& e) {
        // The server sends this body; it must parse back as JSON holding the message.
        if (!nlohmann::json::parse(live::error_body(e.what())).contains("error")) __builtin_trap();
    }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::string_view rest = tirpol::fuzz::as_text(data, size);
    const std::string after = take_line(rest), cookie = take_line(rest), client = take_line(rest);
    parse_or_answer_400([&] { (void)live::parse_after(after); });
    (void)live::request_authorised("0123456789abcdef0123456789abcdef", "", "", cookie,
                                   "tirpol_token");
    (void)live::cookie_value(cookie, "tirpol_token");
    parse_or_answer_400([&] {
        const auto request = live::parse_capture_request(rest);
        if (request.plan.empty() || request.output.empty()) __builtin_trap();
    });
    parse_or_answer_400([&] { (void)tirpol::json_text(live::parse_observation(client, rest)); });
    return 0;
}
