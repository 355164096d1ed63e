// The live view's HTTP server against clients that misbehave, over raw loopback sockets: what it
// refuses it refuses from the headers (a huge declared body is answered 413 before a byte of it is
// sent), a chunked body is cut off at the limit, a request head without end is cut off, idle and
// half-open connections do not keep /api/status from answering, the connection count is capped,
// stored observations are bounded, and a page from another origin can start nothing.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "served_live_view.h"
#include "test_support.h"
#include "tirpol/core/error.h"

namespace tirpol::live {
namespace {

using namespace std::chrono_literals;
using test::raw_request;
using test::RawConnection;
using test::ServedLiveView;

std::string post(const ServedLiveView& s, const std::string& path, const std::string& body,
                 const std::string& extra_headers,
                 const std::string& content_type = "application/json") {
    return "POST " + path + " HTTP/1.1\r\nHost: " + s.host() + "\r\nContent-Type: " + content_type +
           "\r\nContent-Length: " + std::to_string(body.size()) + "\r\n" + extra_headers + "\r\n" +
           body;
}

std::string get(const ServedLiveView& s, const std::string& path,
                const std::string& extra_headers = "") {
    return "GET " + path + " HTTP/1.1\r\nHost: " + s.host() + "\r\n" + extra_headers + "\r\n";
}

TEST(LiveServerLimits, AHugeDeclaredBodyIsRefusedWith413BeforeItIsSent) {
    ServedLiveView s("127.0.0.1");
    RawConnection c(s.server.port());
    ASSERT_TRUE(c.connected());
    // 2.5 GB declared; not one byte of it is sent. The answer comes from the headers alone.
    ASSERT_TRUE(c.send("POST /api/observations?client=a HTTP/1.1\r\nHost: " + s.host() +
                       "\r\nOrigin: " + s.origin() +
                       "\r\nContent-Type: application/json\r\nContent-Length: 2500000000\r\n\r\n"));
    const std::string response = c.receive(3s);
    EXPECT_EQ(RawConnection::status_of(response), 413) << response;
    EXPECT_NE(response.find("2500000000"), std::string::npos) << response;
    // With "Expect: 100-continue" the client is told before it sends the body, too.
    RawConnection e(s.server.port());
    ASSERT_TRUE(e.send("POST /api/observations?client=a HTTP/1.1\r\nHost: " + s.host() +
                       "\r\nOrigin: " + s.origin() +
                       "\r\nContent-Type: application/json\r\nExpect: "
                       "100-continue\r\nContent-Length: 2500000000\r\n\r\n"));
    const std::string expect = e.receive(3s);
    EXPECT_EQ(RawConnection::status_of(expect), 413) << expect;
    EXPECT_EQ(expect.find("100 Continue"), std::string::npos) << expect;
}

TEST(LiveServerLimits, AChunkedBodyIsCutOffAtTheLimitWhileItStreams) {
    ServedLiveView s("127.0.0.1");
    RawConnection c(s.server.port());
    ASSERT_TRUE(c.send("POST /api/observations?client=a HTTP/1.1\r\nHost: " + s.host() +
                       "\r\nOrigin: " + s.origin() +
                       "\r\nContent-Type: application/json\r\nTransfer-Encoding: chunked\r\n\r\n"));
    // 16 KiB chunks: the server answers 413 once the body passes the limit and stops reading.
    const std::string chunk = "4000\r\n" + std::string(0x4000, 'x') + "\r\n";
    int sent = 0;
    for (; sent < 8 && c.send(chunk); ++sent) {  // 128 KiB, twice the limit
    }
    const std::string response = c.receive(3s);
    EXPECT_EQ(RawConnection::status_of(response), 413) << response;
    const std::string stored = raw_request(s.server.port(), get(s, "/api/observations"));
    EXPECT_EQ(nlohmann::json::parse(RawConnection::body_of(stored)), nlohmann::json::object())
        << stored;
}

TEST(LiveServerLimits, ARequestHeadWithoutEndIsCutOffAtItsLimit) {
    ServedLiveView s("127.0.0.1");
    RawConnection c(s.server.port());
    // One header line of 1 MiB without a newline: the server stops reading at the head limit and
    // closes.
    c.send("GET /api/status HTTP/1.1\r\nHost: " + s.host() + "\r\nX-Long: ");
    const std::string filler(64 * 1024, 'a');
    int sent = 0;
    for (; sent < 16 && c.send(filler); ++sent) {
    }
    const std::string response = c.receive(3s);
    if (!c.closed_by_server()) c.receive(3s);  // after the 400, the close
    EXPECT_TRUE(c.closed_by_server()) << response;
    EXPECT_NE(RawConnection::status_of(response), 200) << response;
    // The server goes on answering others.
    EXPECT_EQ(RawConnection::status_of(raw_request(s.server.port(), get(s, "/api/status"))), 200);
}

TEST(LiveServerLimits, HalfOpenConnectionsDoNotStallStatus) {
    ServedLiveView s("127.0.0.1");
    // Twice the 24 worker threads the server used to have, each connected and silent (or sent half
    // a request line), held open while /api/status is asked for.
    std::vector<std::unique_ptr<RawConnection>> idle;
    for (int i = 0; i < 48; ++i) {
        idle.push_back(std::make_unique<RawConnection>(s.server.port()));
        ASSERT_TRUE(idle.back()->connected());
        if (i % 2) idle.back()->send("GET /api/sta");
    }
    std::this_thread::sleep_for(200ms);  // let the server accept them all
    const auto start = std::chrono::steady_clock::now();
    RawConnection c(s.server.port());
    ASSERT_TRUE(c.send(get(s, "/api/status")));
    const std::string response = c.receive(10s);
    const auto waited = std::chrono::steady_clock::now() - start;
    EXPECT_EQ(RawConnection::status_of(response), 200) << response;
    // Answered while the silent connections are still open: well inside their 5 s idle and head
    // timeouts, so not because the server gave up on them.
    EXPECT_LT(waited, 2500ms)
        << std::chrono::duration_cast<std::chrono::milliseconds>(waited).count() << " ms";
    for (auto& connection : idle) EXPECT_FALSE(connection->closed_by_server());
}

TEST(LiveServerLimits, SlowHeadsAreDroppedAtTheHeadTimeoutAndConnectionsAreCapped) {
    RequestLimits limits;
    limits.head_timeout = 400ms;
    limits.max_connections = 4;
    ServedLiveView s("127.0.0.1", test::live_test_options(), limits);
    // A head sent one byte every 100 ms never completes within 400 ms: the server closes it.
    RawConnection slow(s.server.port());
    const std::string head = get(s, "/api/status");
    bool closed = false;
    for (std::size_t i = 0; i < head.size() && i < 60 && !closed; ++i) {
        closed = !slow.send(head.substr(i, 1));
        const std::string got = slow.receive(100ms);
        closed = closed || slow.closed_by_server();
        EXPECT_NE(RawConnection::status_of(got), 200)
            << "a head trickled over " << i * 100 << " ms was served";
    }
    EXPECT_TRUE(closed) << "the server kept a 6 s trickle of a request head";
    // Four connections held open: the fifth is answered 503 at once.
    std::vector<std::unique_ptr<RawConnection>> held;
    for (int i = 0; i < 4; ++i) held.push_back(std::make_unique<RawConnection>(s.server.port()));
    std::this_thread::sleep_for(200ms);
    const std::string busy = raw_request(s.server.port(), get(s, "/api/status"), 2s);
    EXPECT_EQ(RawConnection::status_of(busy), 503) << busy;
    held.clear();
    bool served = false;
    for (int i = 0; i < 50 && !served; ++i) {
        served =
            RawConnection::status_of(raw_request(s.server.port(), get(s, "/api/status"))) == 200;
        if (!served) std::this_thread::sleep_for(100ms);
    }
    EXPECT_TRUE(served) << "the server did not recover after the held connections closed";
}

TEST(LiveServerLimits, StoredObservationsAreBoundedInCountAndSize) {
    ServedLiveView s("127.0.0.1");
    const std::size_t clients = RequestLimits{}.max_observation_clients;
    const std::string small = R"({"frames_shown": 1})";
    for (std::size_t i = 0; i < clients; ++i) {
        const auto r =
            raw_request(s.server.port(), post(s, "/api/observations?client=c" + std::to_string(i),
                                              small, "Origin: " + s.origin() + "\r\n"));
        ASSERT_EQ(RawConnection::status_of(r), 200) << r;
    }
    const auto more = raw_request(s.server.port(), post(s, "/api/observations?client=extra", small,
                                                        "Origin: " + s.origin() + "\r\n"));
    EXPECT_EQ(RawConnection::status_of(more), 429) << more;
    // A client already reporting may update its own.
    EXPECT_EQ(RawConnection::status_of(raw_request(
                  s.server.port(),
                  post(s, "/api/observations?client=c0", small, "Origin: " + s.origin() + "\r\n"))),
              200);
    const std::string big = "\"" + std::string(RequestLimits{}.max_body_bytes, 'x') + "\"";
    EXPECT_EQ(RawConnection::status_of(raw_request(
                  s.server.port(),
                  post(s, "/api/observations?client=c1", big, "Origin: " + s.origin() + "\r\n"))),
              413);
}

TEST(LiveServerLimits, HostOriginAndContentTypeMatrix) {
    ServedLiveView s("127.0.0.1");
    const int port = s.server.port();
    const std::string stop = "/api/capture/stop";
    struct Case {
        std::string host, origin, type;
        int status;
    };
    const std::string self = s.host(), evil = "evil.example:" + std::to_string(port);
    for (const Case& c : std::vector<Case>{
             {self, "http://evil.example", "text/plain", 415},
             {self, "http://evil.example", "application/x-www-form-urlencoded", 415},
             {self, "http://evil.example", "application/json", 403},
             {self, "", "application/json", 403},
             {evil, "http://" + evil, "application/json",
              403},  // DNS rebinding: same origin, wrong host
             {self, s.origin(), "text/plain", 415},
             {self, s.origin(), "application/json", 400},  // reaches the handler: no stage here
             {"localhost:" + std::to_string(port), "http://localhost:" + std::to_string(port),
              "application/json", 400},
         }) {
        std::string request = "POST " + stop + " HTTP/1.1\r\nHost: " + c.host +
                              "\r\nContent-Type: " + c.type + "\r\nContent-Length: 2\r\n";
        if (!c.origin.empty()) request += "Origin: " + c.origin + "\r\n";
        const std::string response = raw_request(port, request + "\r\n{}");
        EXPECT_EQ(RawConnection::status_of(response), c.status)
            << c.host << " / " << c.origin << " / " << c.type << ": " << response;
    }
    // GET under a rebinding name, and the CORS preflight of a JSON POST from another site.
    EXPECT_EQ(RawConnection::status_of(
                  raw_request(port, "GET /api/status HTTP/1.1\r\nHost: " + evil + "\r\n\r\n")),
              403);
    const std::string preflight = raw_request(
        port, "OPTIONS /api/capture/start HTTP/1.1\r\nHost: " + self +
                  "\r\nOrigin: http://evil.example\r\nAccess-Control-Request-Method: POST\r\n"
                  "Access-Control-Request-Headers: content-type\r\n\r\n");
    EXPECT_EQ(RawConnection::status_of(preflight), 405) << preflight;
    EXPECT_EQ(preflight.find("Access-Control-Allow"), std::string::npos) << preflight;
}

TEST(LiveServerLimits, BeyondLoopbackTheTokenIsRequiredAndAScriptMaySendItInsteadOfAnOrigin) {
    ServedLiveView s("0.0.0.0");
    const int port = s.server.port();
    const std::string token = s.server.token();
    ASSERT_EQ(token.size(), 32u);
    EXPECT_EQ(RawConnection::status_of(raw_request(port, get(s, "/api/status"))), 401);
    EXPECT_EQ(RawConnection::status_of(
                  raw_request(port, get(s, "/api/status", "X-Tirpol-Token: " + token + "\r\n"))),
              200);
    // A refused POST with a body: refused from the headers, before its (large) body is read.
    EXPECT_EQ(RawConnection::status_of(
                  raw_request(port, post(s, "/api/observations?client=x", std::string(60000, ' '),
                                         "Origin: " + s.origin() + "\r\n"))),
              401);
    EXPECT_EQ(
        RawConnection::status_of(raw_request(port, post(s, "/api/observations?client=x", "{}",
                                                        "X-Tirpol-Token: " + token + "\r\n"))),
        200);
    // The cookie alone (which a browser attaches to any request to this host) does not change
    // state.
    EXPECT_EQ(
        RawConnection::status_of(raw_request(port, post(s, "/api/observations?client=y", "{}",
                                                        "Cookie: tirpol_token=" + token + "\r\n"))),
        403);
}

TEST(LiveServerLimits, CaptureRequestsFromAnotherSiteStartNothingAndErrorsQuoteNoFile) {
    test::TempDir dir("tirpol-live-limits");
    test::write_text(dir.path() / "plan.yaml", "frames_per_angle: 1\nsettle_s: 0.01\n");
    ServedLiveView s("127.0.0.1", test::live_test_options("sim://"));
    const int port = s.server.port();
    const auto session = dir.path() / "session";
    const std::string request = nlohmann::json{
        {"plan", (dir.path() / "plan.yaml").string()},
        {"output",
         session.string()}}.dump();
    // The request the issue reported: another site's simple POST (text/plain, its own Origin).
    const std::string evil = raw_request(
        port,
        post(s, "/api/capture/start", request, "Origin: http://evil.example\r\n", "text/plain"));
    EXPECT_EQ(RawConnection::status_of(evil), 415) << evil;
    std::this_thread::sleep_for(300ms);
    EXPECT_FALSE(std::filesystem::exists(session));
    const auto status =
        nlohmann::json::parse(RawConnection::body_of(raw_request(port, get(s, "/api/status"))));
    EXPECT_EQ(status["capture"]["phase"], "idle") << status.dump();

    // A file that is not a plan is named, its contents never echoed.
    test::write_text(dir.path() / "secret.txt", "password=hunter2\n");
    for (const auto& file : {dir.path() / "secret.txt", std::filesystem::path("/etc/passwd")}) {
        const std::string body =
            nlohmann::json{{"plan", file.string()}, {"output", (dir.path() / "o").string()}}.dump();
        const std::string r = raw_request(
            port, post(s, "/api/capture/start", body, "Origin: " + s.origin() + "\r\n"));
        EXPECT_EQ(RawConnection::status_of(r), 400) << r;
        EXPECT_NE(r.find(file.string()), std::string::npos) << r;
        EXPECT_EQ(r.find("hunter2"), std::string::npos) << r;
        EXPECT_EQ(r.find("root:"), std::string::npos) << r;
    }
    // Invalid UTF-8 in the plan's metadata: a 400 naming the file, line and column, not a 500 with
    // an exception's text (the reader checks the whole file is UTF-8 before parsing it).
    test::write_text(dir.path() / "utf8.yaml",
                     "frames_per_angle: 1\nmetadata:\n  site: \"\xff\xfe\"\n");
    const std::string body = nlohmann::json{{"plan", (dir.path() / "utf8.yaml").string()},
                                            {"output", (dir.path() / "u").string()}}
                                 .dump();
    const std::string r =
        raw_request(port, post(s, "/api/capture/start", body, "Origin: " + s.origin() + "\r\n"));
    EXPECT_EQ(RawConnection::status_of(r), 400) << r;
    EXPECT_NE(r.find("utf8.yaml:3:10: invalid UTF-8 (byte 0xFF)"), std::string::npos) << r;
    EXPECT_EQ(r.find("json.exception"), std::string::npos) << r;
    // The page's own request starts the plan.
    const std::string ok =
        raw_request(port, post(s, "/api/capture/start", request, "Origin: " + s.origin() + "\r\n"));
    EXPECT_EQ(RawConnection::status_of(ok), 200) << ok;
}

TEST(LiveServerLimits, SnapshotRequestsFromAnotherSiteWriteNothing) {
    test::TempDir dir("tirpol-live-snapshot");
    LiveViewOptions options = test::live_test_options();
    options.snapshot_dir = (dir.path() / "snaps").string();
    std::filesystem::create_directories(options.snapshot_dir);
    ServedLiveView s("127.0.0.1", options);
    const int port = s.server.port();
    const auto files = [&] {
        return std::distance(std::filesystem::directory_iterator(options.snapshot_dir),
                             std::filesystem::directory_iterator{});
    };
    struct Case {
        std::string origin, type;
        int status;
    };
    for (const Case& c : std::vector<Case>{{"http://evil.example", "text/plain", 415},
                                           {"http://evil.example", "application/json", 403},
                                           {"", "application/json", 403},
                                           {"null", "application/json", 403}}) {
        const std::string extra = c.origin.empty() ? "" : "Origin: " + c.origin + "\r\n";
        const std::string r = raw_request(port, post(s, "/api/snapshot", "{}", extra, c.type));
        EXPECT_EQ(RawConnection::status_of(r), c.status) << c.origin << " / " << c.type << r;
    }
    // A body over the limit is refused from its Content-Length.
    const std::string huge =
        raw_request(port, "POST /api/snapshot HTTP/1.1\r\nHost: " + s.host() +
                              "\r\nContent-Type: application/json\r\nOrigin: " + s.origin() +
                              "\r\nContent-Length: 2500000000\r\n\r\n");
    EXPECT_EQ(RawConnection::status_of(huge), 413) << huge;
    EXPECT_EQ(files(), 0);
    // The page's own request writes a snapshot (an EXR and a PNG of S0: no stage here).
    std::string ok;
    for (int i = 0; i < 100 && RawConnection::status_of(ok) != 200; ++i) {
        ok = raw_request(port, post(s, "/api/snapshot", "{}", "Origin: " + s.origin() + "\r\n"));
        std::this_thread::sleep_for(20ms);  // until the first frame arrived
    }
    EXPECT_EQ(RawConnection::status_of(ok), 200) << ok;
    const auto answer = nlohmann::json::parse(RawConnection::body_of(ok));
    EXPECT_EQ(answer["channels"], nlohmann::json::array({"S0"}));
    EXPECT_EQ(files(), 2) << answer.dump();
}

TEST(LiveServerLimits, ASnapshotWithoutASnapshotFolderIsA400NamingTheOption) {
    ServedLiveView s("127.0.0.1");
    const std::string r = raw_request(
        s.server.port(), post(s, "/api/snapshot", "{}", "Origin: " + s.origin() + "\r\n"));
    EXPECT_EQ(RawConnection::status_of(r), 400) << r;
    EXPECT_NE(r.find("--snapshot-dir"), std::string::npos) << r;
}

TEST(LiveServerLimits, OptionsOutOfRangeAreErrorsNamingTheOption) {
    LiveViewOptions view = test::live_test_options();
    view.cycle.settle_s = std::numeric_limits<double>::quiet_NaN();
    try {
        validate(view);
        ADD_FAILURE() << "settle NaN accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("--settle-s"), std::string::npos) << e.what();
    }
    view = test::live_test_options();
    for (const double bad : {-0.1, std::numeric_limits<double>::infinity()}) {
        view.cycle.settle_s = bad;
        EXPECT_THROW(validate(view), Error) << bad;
    }
    view = test::live_test_options();
    view.cycle.frames_per_angle = 0;
    EXPECT_THROW(validate(view), Error);
    for (const int port : {-1, 65536, 70000}) {
        ServerOptions server;
        server.port = port;
        try {
            validate(server);
            ADD_FAILURE() << "port " << port << " accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("--port"), std::string::npos) << e.what();
        }
    }
    ServerOptions ok;
    ok.port = 65535;
    EXPECT_NO_THROW(validate(ok));
}

}  // namespace
}  // namespace tirpol::live
