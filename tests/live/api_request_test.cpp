// What the live view's API reads from a request (live/api_request.h), without a socket: each piece
// a page or anyone on the network controls is accepted exactly in its documented form
// (docs/live.md) and anything else is a tirpol::Error whose 400 body is valid JSON, even when it
// quotes bytes that are not UTF-8 (nlohmann's own parse messages did, and dumping them threw
// type_error 316).

#include "api_request.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tirpol/core/error.h"
#include "tirpol/core/utf8.h"

namespace tirpol::live {
namespace {

using testing::HasSubstr;
using testing::ThrowsMessage;

TEST(ApiRequest, AfterIsADecimalSequenceNumberOrAbsent) {
    EXPECT_EQ(parse_after(std::nullopt), 0u);
    EXPECT_EQ(parse_after("0"), 0u);
    EXPECT_EQ(parse_after("18446744073709551615"), 18446744073709551615u);
    // std::stoull took "-1" as 2^64 − 1 (a frame that never comes) and " 7" or "7x" as 7.
    for (const char* bad : {"", "-1", " 7", "7x", "1e9", "18446744073709551616", "0x10"})
        EXPECT_THAT([&] { (void)parse_after(std::string(bad)); },
                    ThrowsMessage<Error>(HasSubstr("after: expected")))
            << "'" << bad << "'";
}

TEST(ApiRequest, CaptureStartTakesPlanOutputAndOptionalResume) {
    const auto r =
        parse_capture_request(R"({"plan": "plans/p.yaml", "output": "s1", "resume": true})");
    EXPECT_EQ(r.plan, "plans/p.yaml");
    EXPECT_EQ(r.output, "s1");
    EXPECT_TRUE(r.resume);
    EXPECT_FALSE(parse_capture_request(R"({"plan": "p", "output": "o"})").resume);
    const std::pair<const char*, const char*> bad[] = {
        {"not json", "expected a JSON object"},
        {"[1, 2]", "expected a JSON object"},
        {R"({"plan": "p"})", "'output' must be a non-empty string"},
        {R"({"plan": "", "output": "o"})", "'plan' must be a non-empty string"},
        {R"({"plan": 3, "output": "o"})", "'plan' must be a non-empty string"},
        {R"({"plan": "p", "output": "o", "resume": "yes"})", "'resume' must be true or false"},
        {R"({"plan": "p", "output": "o", "frames": 3})", "unknown key 'frames'"},
    };
    for (const auto& [body, message] : bad)
        EXPECT_THAT([&] { (void)parse_capture_request(body); },
                    ThrowsMessage<Error>(HasSubstr(message)))
            << body;
}

TEST(ApiRequest, ErrorBodiesAreValidJsonWhateverBytesTheRequestCarried) {
    const std::string body = "{\"plan\": \"caf\xE9\", \xFF\xFE";  // invalid UTF-8, invalid JSON
    std::string message;
    try {
        (void)parse_capture_request(body);
    } catch (const Error& e) {
        message = e.what();
    }
    const auto reply = nlohmann::json::parse(error_body(message));  // throws if not valid JSON
    EXPECT_THAT(reply.at("error").get<std::string>(), testing::HasSubstr("expected a JSON object"));
    EXPECT_TRUE(is_valid_utf8(reply.at("error").get<std::string>()));
}

TEST(ApiRequest, ObservationsNeedAClientAndAJsonBody) {
    EXPECT_EQ(parse_observation("page-1", R"({"frames": 3})").at("frames"), 3);
    EXPECT_THAT([] { (void)parse_observation(std::nullopt, "{}"); },
                ThrowsMessage<Error>(HasSubstr("?client=ID")));
    EXPECT_THAT([] { (void)parse_observation("", "{}"); },
                ThrowsMessage<Error>(HasSubstr("?client=ID")));
    EXPECT_THAT([] { (void)parse_observation("p", "{"); },
                ThrowsMessage<Error>(HasSubstr("not JSON")));
}

TEST(ApiRequest, TokenComesFromTheQueryTheHeaderOrTheCookieOnlyWhenEqual) {
    const std::string token = "0123456789abcdef0123456789abcdef";
    EXPECT_EQ(cookie_value("a=1; tirpol_token=xyz; b=2", "tirpol_token"), "xyz");
    EXPECT_EQ(cookie_value("tirpol_tokenx=1; xtirpol_token=2", "tirpol_token"), "");
    EXPECT_TRUE(request_authorised("", "", "", "", "tirpol_token"));  // loopback: no token required
    EXPECT_TRUE(request_authorised(token, token, "", "", "tirpol_token"));
    EXPECT_TRUE(request_authorised(token, "", token, "", "tirpol_token"));
    EXPECT_TRUE(request_authorised(token, "", "", "x=1; tirpol_token=" + token, "tirpol_token"));
    EXPECT_FALSE(request_authorised(token, "", "", "", "tirpol_token"));
    EXPECT_FALSE(request_authorised(token, token.substr(1), token + "0",
                                    "tirpol_token=" + token.substr(0, 31), "tirpol_token"));
}

}  // namespace
}  // namespace tirpol::live
