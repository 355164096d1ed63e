// The request policy of the live view (request_policy.h, threat model in docs/live.md), rule by
// rule: a request another web page can make, or one reaching the server under a rebinding DNS name,
// is refused from its line and headers alone; the page's own requests pass.

#include "request_policy.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "access.h"

namespace tirpol::live {
namespace {

constexpr int kPort = 41235;
const std::string kSelf = "127.0.0.1:41235";

RequestPolicy loopback_policy() { return RequestPolicy(allowed_hosts("127.0.0.1", kPort), ""); }

RequestFacts page_post(const std::string& body_length = "20") {
    RequestFacts r;
    r.method = "POST";
    r.host = kSelf;
    r.origin = "http://" + kSelf;
    r.content_type = "application/json";
    r.content_length = body_length;
    return r;
}

int status_of(const RequestPolicy& policy, const RequestFacts& request) {
    const auto refusal = policy.check(request);
    return refusal ? refusal->status : 0;
}

TEST(RequestPolicy, LoopbackHostsAreTheLoopbackNamesWithThePort) {
    const RequestPolicy p = loopback_policy();
    for (const char* host :
         {"127.0.0.1:41235", "localhost:41235", "LOCALHOST:41235", "[::1]:41235"})
        EXPECT_TRUE(p.host_allowed(host)) << host;
    for (const char* host : {"evil.example:41235", "127.0.0.1", "127.0.0.1:41236", "localhost", "",
                             "127.0.0.1:41235x"})
        EXPECT_FALSE(p.host_allowed(host)) << host;
    EXPECT_TRUE(p.origin_allowed("http://localhost:41235"));
    EXPECT_FALSE(p.origin_allowed("https://localhost:41235"));
    EXPECT_FALSE(p.origin_allowed("http://evil.example"));
    EXPECT_FALSE(p.origin_allowed("null"));
}

TEST(RequestPolicy, TheHostHeaderOfADnsRebindingPageIsRefused) {
    RequestFacts r;
    r.method = "GET";
    r.host = "evil.example:41235";  // the attacker's name, now resolving to 127.0.0.1
    const auto refusal = loopback_policy().check(r);
    ASSERT_TRUE(refusal);
    EXPECT_EQ(refusal->status, 403);
    EXPECT_NE(refusal->message.find("evil.example"), std::string::npos);
    r.host = kSelf;
    EXPECT_FALSE(loopback_policy().check(r));
}

TEST(RequestPolicy, StateChangesNeedJsonAndThisOrigin) {
    const RequestPolicy p = loopback_policy();
    EXPECT_EQ(status_of(p, page_post()), 0);
    RequestFacts r = page_post();
    r.content_type = "application/json; charset=utf-8";
    EXPECT_EQ(status_of(p, r), 0);
    // Every content type a CORS simple request may carry is refused, whatever the origin.
    for (const char* type :
         {"text/plain", "text/plain; charset=UTF-8", "application/x-www-form-urlencoded",
          "multipart/form-data; boundary=x", ""}) {
        r = page_post();
        r.content_type = type;
        EXPECT_EQ(status_of(p, r), 415) << type;
        r.origin = "http://evil.example";
        EXPECT_EQ(status_of(p, r), 415) << type;
    }
    for (const char* origin :
         {"http://evil.example", "http://127.0.0.1:41236", "https://127.0.0.1:41235", "null", ""}) {
        r = page_post();
        r.origin = origin;
        EXPECT_EQ(status_of(p, r), 403) << origin;
    }
    // A script on this machine may send the token instead of an Origin (with a token-protected
    // bind).
    const RequestPolicy with_token(allowed_hosts("127.0.0.1", kPort), "t0k3n");
    r = page_post();
    r.origin.clear();
    r.explicit_token = true;
    EXPECT_EQ(status_of(with_token, r), 0);
    // The cookie alone is not enough for a state change: a browser attaches it by itself.
    r.explicit_token = false;
    r.cookie_token = true;
    EXPECT_EQ(status_of(with_token, r), 403);
    r.origin = "http://" + kSelf;
    EXPECT_EQ(status_of(with_token, r), 0);
}

TEST(RequestPolicy, MethodsOtherThanGetHeadPostAreRefusedAndGetCarriesNoBody) {
    const RequestPolicy p = loopback_policy();
    RequestFacts r;
    r.host = kSelf;
    for (const char* method : {"OPTIONS", "PUT", "DELETE", "PATCH", "TRACE"}) {
        r.method = method;
        EXPECT_EQ(status_of(p, r), 405) << method;  // a CORS preflight never gets an Allow-Origin
    }
    r.method = "GET";
    EXPECT_EQ(status_of(p, r), 0);
    r.content_length = "10";
    EXPECT_EQ(status_of(p, r), 400);
    r.content_length.reset();
    r.transfer_encoding = "chunked";
    EXPECT_EQ(status_of(p, r), 400);
}

TEST(RequestPolicy, BodySizeIsDecidedFromTheHeadersBeforeReading) {
    const RequestPolicy p = loopback_policy();
    const std::size_t limit = p.limits().max_body_bytes;
    EXPECT_EQ(status_of(p, page_post(std::to_string(limit))), 0);
    EXPECT_EQ(status_of(p, page_post(std::to_string(limit + 1))), 413);
    EXPECT_EQ(status_of(p, page_post("2500000000")), 413);
    EXPECT_EQ(status_of(p, page_post("99999999999999999999999")), 400);  // beyond 64 bits
    EXPECT_EQ(status_of(p, page_post("-1")), 400);
    EXPECT_EQ(status_of(p, page_post("1e9")), 400);
    RequestFacts r = page_post();
    r.content_length.reset();
    EXPECT_EQ(status_of(p, r), 411);
    r.transfer_encoding = "chunked";  // capped while it streams in (live_server_limits_test)
    EXPECT_EQ(status_of(p, r), 0);
    r.transfer_encoding = "gzip, chunked";
    EXPECT_EQ(status_of(p, r), 501);
}

TEST(RequestPolicy, BeyondLoopbackEveryRequestNeedsTheTokenAndTheHostIsThisMachine) {
    const RequestPolicy p(allowed_hosts("0.0.0.0", kPort), "t0k3n");
    RequestFacts r;
    r.method = "GET";
    r.host = kSelf;
    EXPECT_EQ(status_of(p, r), 401);
    r.explicit_token = true;
    EXPECT_EQ(status_of(p, r), 0);
    r.host = "evil.example:41235";
    EXPECT_EQ(status_of(p, r), 403);
    // Every interface address of this machine is a valid Host for a wildcard bind.
    for (const std::string& a : interface_addresses()) {
        const std::string host = (a.find(':') != std::string::npos ? "[" + a + "]" : a) + ":41235";
        EXPECT_TRUE(p.host_allowed(host)) << host;
    }
    // A specific address: that one and the loopback names only.
    const auto hosts = allowed_hosts("192.0.2.7", kPort);
    EXPECT_NE(std::find(hosts.begin(), hosts.end(), "192.0.2.7:41235"), hosts.end());
    EXPECT_EQ(std::find(hosts.begin(), hosts.end(), "192.0.2.8:41235"), hosts.end());
}

}  // namespace
}  // namespace tirpol::live
