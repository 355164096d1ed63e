// The HTTP side in-process, with an httplib client as the page: the page and its files are served
// from the binary, /api/frame hands out each newer frame once, decodable, at the client's pace; on
// loopback no token is needed, bound beyond loopback every request without the printed token is
// refused with 401.

#include "tirpol/live/live_server.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <thread>

#include "access.h"
#include "decoded_image.h"
#include "error_of.h"
#include "httplib_after_eigen.h"
#include "served_live_view.h"
#include "tirpol/core/error.h"

using tirpol::test::error_of;

namespace tirpol::live {
namespace {

using namespace std::chrono_literals;

using Served = test::ServedLiveView;
constexpr const char* kCamera = test::kLiveTestCamera;

TEST(LiveServer, ServesThePageAndNewerFramesOnLoopback) {
    Served s("127.0.0.1");
    EXPECT_TRUE(s.server.token().empty());
    EXPECT_EQ(s.server.url(), "http://127.0.0.1:" + std::to_string(s.server.port()) + "/");
    httplib::Client client("127.0.0.1", s.server.port());
    auto page = client.Get("/");
    ASSERT_TRUE(page);
    EXPECT_EQ(page->status, 200);
    EXPECT_NE(page->body.find("<canvas id=\"s0\""), std::string::npos);
    auto script = client.Get("/live.js");
    ASSERT_TRUE(script);
    EXPECT_NE(script->body.find("function decode"), std::string::npos);

    auto first = client.Get("/api/frame?after=0");
    ASSERT_TRUE(first);
    ASSERT_EQ(first->status, 200);
    const std::uint64_t seq = std::stoull(first->get_header_value("X-Sequence"));
    const auto a = test::decode_live_image(first->body);
    ASSERT_EQ(a.codes.size(), 1u);
    EXPECT_EQ(a.header["width"], 32);
    EXPECT_NEAR(a.value(0, 0), 1500.0, 20.0);  // 1500 counts ± noise
    auto second = client.Get(("/api/frame?after=" + std::to_string(seq)).c_str());
    ASSERT_TRUE(second);
    ASSERT_EQ(second->status, 200);
    EXPECT_GT(std::stoull(second->get_header_value("X-Sequence")), seq);
    EXPECT_GT(test::decode_live_image(second->body).header["frame_id"].get<std::uint64_t>(),
              a.header["frame_id"].get<std::uint64_t>());

    const auto status = nlohmann::json::parse(client.Get("/api/status")->body);
    EXPECT_GE(status["camera"]["grabbed"].get<int>(), 2);
    EXPECT_FALSE(status.contains("stage"));
    // No stage: Stokes never arrives (204 after the long poll) and capture is refused with a
    // reason.
    EXPECT_EQ(client.Get("/api/stokes?after=0")->status, 204);
    auto capture = client.Post("/api/capture/start", {{"Origin", s.origin()}},
                               R"({"plan":"p.yaml","output":"o"})", "application/json");
    ASSERT_TRUE(capture);
    EXPECT_EQ(capture->status, 400);
    EXPECT_NE(capture->body.find("--stage"), std::string::npos) << capture->body;
}

TEST(LiveServer, TheRegionReadoutAveragesTheLatestFrameAndRefusesBadQueriesByName) {
    Served s("127.0.0.1");
    httplib::Client client("127.0.0.1", s.server.port());
    ASSERT_EQ(client.Get("/api/frame?after=0")->status, 200);  // a frame has arrived
    auto r = client.Get("/api/region?x0=2&y0=3&x1=11&y1=12&dolp_min=0.05");
    ASSERT_TRUE(r);
    ASSERT_EQ(r->status, 200) << r->body;
    const auto j = nlohmann::json::parse(r->body);
    EXPECT_EQ(j["live"]["S0"]["count"], 100);
    EXPECT_NEAR(j["live"]["S0"]["mean"].get<double>(), 1500.0, 20.0);  // 1500 counts ± noise
    EXPECT_EQ(j["live"]["S0"]["units"], "counts");
    // A flat field: the gradient energy is that of the noise alone, 4σ² for independent pixels.
    const double sigma = j["live"]["S0"]["std"];
    EXPECT_NEAR(j["focus"]["value"].get<double>(), 4.0 * sigma * sigma, 2.0 * sigma * sigma);
    EXPECT_FALSE(j.contains("cycle")) << "no stage, no cycle";
    for (const char* bad : {"/api/region?x0=2&y0=3&x1=11", "/api/region?x0=a&y0=3&x1=11&y1=12",
                            "/api/region?x0=0&y0=0&x1=1&y1=1&dolp_min=2",
                            "/api/region?x0=500&y0=500&x1=600&y1=600"}) {
        auto b = client.Get(bad);
        ASSERT_TRUE(b) << bad;
        EXPECT_EQ(b->status, 400) << bad;
        EXPECT_NE(b->body.find("region"), std::string::npos) << bad << ": " << b->body;
    }
}

TEST(LiveServer, BeyondLoopbackEveryRequestNeedsTheToken) {
    Served s("0.0.0.0");
    const std::string token = s.server.token();
    ASSERT_EQ(token.size(), 32u);
    EXPECT_NE(s.server.url().find("?token=" + token), std::string::npos);
    // The URL to open names an address of this machine another one can reach, never the wildcard.
    EXPECT_EQ(s.server.url().find("0.0.0.0"), std::string::npos) << s.server.url();
    // Every URL printed names a non-loopback address of this machine (or 127.0.0.1 without one).
    const std::vector<std::string> urls = s.server.urls();
    ASSERT_FALSE(urls.empty());
    EXPECT_EQ(urls.front(), s.server.url());
    const std::vector<std::string> own = interface_addresses();
    for (const std::string& address : reachable_addresses("0.0.0.0")) {
        EXPECT_NE(address, "0.0.0.0");
        if (address == "127.0.0.1") continue;
        EXPECT_FALSE(is_loopback_address(address)) << address;
        EXPECT_NE(std::find(own.begin(), own.end(), address), own.end()) << address;
    }
    EXPECT_EQ(reachable_addresses("192.0.2.7"), std::vector<std::string>{"192.0.2.7"});
    httplib::Client client("127.0.0.1", s.server.port());
    for (const char* path :
         {"/", "/live.js", "/api/status", "/api/frame?after=0", "/api/observations"}) {
        auto r = client.Get(path);
        ASSERT_TRUE(r) << path;
        EXPECT_EQ(r->status, 401) << path;
        EXPECT_EQ(r->body.find("canvas"), std::string::npos);
    }
    EXPECT_EQ(client.Post("/api/capture/stop", "", "application/json")->status, 401);
    EXPECT_EQ(client.Get(("/api/status?token=" + token.substr(0, 31) + "0").c_str())->status,
              token.back() == '0' ? 200 : 401);
    EXPECT_EQ(client.Get(("/?token=" + token).c_str())->status, 200);
    EXPECT_EQ(client.Get("/api/status", {{"X-Tirpol-Token", token}})->status, 200);
    // The page's script and style sheet are fetched without a query: the cookie set with the page
    // covers them.
    const auto page = client.Get(("/?token=" + token).c_str());
    const std::string cookie = page->get_header_value("Set-Cookie");
    EXPECT_NE(cookie.find("tirpol_token=" + token), std::string::npos) << cookie;
    EXPECT_NE(cookie.find("HttpOnly"), std::string::npos) << cookie;
    EXPECT_EQ(client.Get("/live.js", {{"Cookie", "other=1; tirpol_token=" + token}})->status, 200);
    EXPECT_EQ(client.Get("/live.js", {{"Cookie", "tirpol_token=" + std::string(32, '0')}})->status,
              401);
}

TEST(Access, LoopbackAddressesAndTokens) {
    EXPECT_TRUE(is_loopback_address("127.0.0.1"));
    EXPECT_TRUE(is_loopback_address("127.1.2.3"));
    EXPECT_TRUE(is_loopback_address("::1"));
    EXPECT_TRUE(is_loopback_address("localhost"));
    EXPECT_FALSE(is_loopback_address("0.0.0.0"));
    EXPECT_FALSE(is_loopback_address("192.168.1.20"));
    const std::string a = make_access_token(), b = make_access_token();
    EXPECT_EQ(a.size(), 32u);
    EXPECT_NE(a, b);
    EXPECT_TRUE(token_matches(a, a));
    EXPECT_FALSE(token_matches(b, a));
    EXPECT_FALSE(token_matches("", ""));
    EXPECT_FALSE(token_matches(a.substr(0, 31), a));
}

}  // namespace
}  // namespace tirpol::live

namespace tirpol::live {
namespace {

TEST(LiveView, BadInputsAreErrorsNamingWhatIsWrong) {
    LiveViewOptions o;
    o.camera_uri = "sim://uniform?widht=32";
    EXPECT_NE(error_of([&] { LiveView v(o); }).find("widht"), std::string::npos);
    o.camera_uri = kCamera;
    o.unit = DisplayUnit::Temperature;
    EXPECT_NE(error_of([&] { LiveView v(o); }).find("--calibration"), std::string::npos);
    o.unit = DisplayUnit::Counts;
    o.stage_uri = "nostage://x";
    EXPECT_NE(error_of([&] { LiveView v(o); }).find("nostage"), std::string::npos);
}

TEST(LiveServer, APortInUseIsAnErrorNamingIt) {
    Served first("127.0.0.1");
    LiveView view(test::live_test_options());
    const std::string message = error_of([&] {
        LiveServer second(view, {"127.0.0.1", first.server.port()});
    });
    EXPECT_NE(message.find(std::to_string(first.server.port())), std::string::npos) << message;
}

}  // namespace
}  // namespace tirpol::live
