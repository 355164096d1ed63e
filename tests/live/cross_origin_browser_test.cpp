// A web page the operator's browser opens must not drive the live view. Headless Chromium opens a
// page served by a second local HTTP server on another port (another origin) that tries what any
// site can: fetch() POSTs to the live view's /api/capture/start — a CORS "simple request"
// (text/plain, no-cors, which the browser sends without asking) and a JSON one (which needs a
// preflight) — and a simple POST to /api/observations. No capture may start, no session be written,
// nothing be stored. A third server (the witness) receives the same simple POST, proving the
// browser does send such requests between loopback ports. A missing chromium fails the test: it
// never skips.

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>

#include "child_process.h"
#include "find_on_path.h"
#include "httplib_after_eigen.h"
#include "served_live_view.h"
#include "test_support.h"

namespace tirpol::live {
namespace {

using namespace std::chrono_literals;

using test::find_on_path;

/// An httplib server on a free loopback port, serving on its own thread until destroyed.
struct SideServer {
    httplib::Server server;
    std::thread thread;
    int port = 0;
    void start() {
        port = server.bind_to_any_port("127.0.0.1");
        thread = std::thread([this] { server.listen_after_bind(); });
        for (int i = 0; i < 200 && !server.is_running(); ++i) std::this_thread::sleep_for(10ms);
    }
    ~SideServer() {
        server.stop();
        if (thread.joinable()) thread.join();
    }
};

std::string attacker_page(int live_port, int witness_port, const std::string& plan,
                          const std::string& output) {
    const std::string body = nlohmann::json{{"plan", plan}, {"output", output}}.dump();
    return R"(<!doctype html><meta charset="utf-8"><title>another site</title><script>
const live = 'http://127.0.0.1:)" +
           std::to_string(live_port) + R"(';
const witness = 'http://127.0.0.1:)" +
           std::to_string(witness_port) + R"(';
const body = )" +
           nlohmann::json(body).dump() + R"(;
const results = {};
async function attempt(name, url, init) {
  try { const r = await fetch(url, init); results[name] = r.type === 'opaque' ? 'opaque' : 'status ' + r.status; }
  catch (e) { results[name] = 'blocked: ' + e.name; }
}
(async () => {
  const simple = { method: 'POST', mode: 'no-cors', headers: { 'Content-Type': 'text/plain' }, body };
  await attempt('witness', witness + '/sink', simple);
  await attempt('simple', live + '/api/capture/start', simple);
  await attempt('form', live + '/api/capture/start',
                { method: 'POST', mode: 'no-cors', headers: { 'Content-Type': 'application/x-www-form-urlencoded' }, body });
  await attempt('json', live + '/api/capture/start',
                { method: 'POST', mode: 'cors', headers: { 'Content-Type': 'application/json' }, body });
  await attempt('observe', live + '/api/observations?client=evil', { method: 'POST', mode: 'no-cors', body: '{}' });
  await attempt('snapshot_simple', live + '/api/snapshot', { method: 'POST', mode: 'no-cors', headers: { 'Content-Type': 'text/plain' }, body: '{}' });
  await attempt('snapshot_form', live + '/api/snapshot',
                { method: 'POST', mode: 'no-cors', headers: { 'Content-Type': 'application/x-www-form-urlencoded' }, body: '{}' });
  await attempt('snapshot_json', live + '/api/snapshot',
                { method: 'POST', mode: 'cors', headers: { 'Content-Type': 'application/json' }, body: '{}' });
  await fetch('/done', { method: 'POST', body: JSON.stringify(results) });
})();
</script>)";
}

TEST(LiveCrossOrigin, APageFromAnotherOriginCannotStartACaptureOrStoreAnything) {
    const auto chromium = find_on_path("chromium");
    ASSERT_TRUE(chromium)
        << "chromium is not on PATH (Debian package chromium): the live-view tests need it";
    test::TempDir dir("tirpol-live-cross-origin");
    test::write_text(dir.path() / "plan.yaml", "frames_per_angle: 1\nsettle_s: 0.01\n");
    const auto session = dir.path() / "session";

    live::LiveViewOptions options = test::live_test_options("sim://");
    options.snapshot_dir = (dir.path() / "snaps").string();
    std::filesystem::create_directories(options.snapshot_dir);
    test::ServedLiveView live("127.0.0.1", options);

    std::atomic<int> witnessed{0};
    SideServer witness;
    witness.server.Post("/sink", [&](const httplib::Request&, httplib::Response& res) {
        ++witnessed;
        res.set_content("ok", "text/plain");
    });
    witness.start();

    std::mutex mutex;
    std::string done;
    SideServer attacker;
    const std::string page = attacker_page(live.server.port(), witness.port,
                                           (dir.path() / "plan.yaml").string(), session.string());
    attacker.server.Get("/evil.html", [&](const httplib::Request&, httplib::Response& res) {
        res.set_content(page, "text/html; charset=utf-8");
    });
    attacker.server.Post("/done", [&](const httplib::Request& req, httplib::Response& res) {
        std::lock_guard lock(mutex);
        done = req.body;
        res.set_content("ok", "text/plain");
    });
    attacker.start();
    ASSERT_NE(attacker.port, live.server.port());

    test::ChildProcess browser(
        {chromium->string(), "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
         "--user-data-dir=" + (dir.path() / "chromium").string(),
         "http://127.0.0.1:" + std::to_string(attacker.port) + "/evil.html"},
        dir.path() / "chromium.log");
    bool finished = false;
    for (int i = 0; i < 600 && !finished; ++i) {  // at most 60 s
        {
            std::lock_guard lock(mutex);
            finished = !done.empty();
        }
        if (!finished) std::this_thread::sleep_for(100ms);
    }
    ASSERT_TRUE(finished) << "the attacker page never reported";
    const auto results = nlohmann::json::parse(done);
    // The browser did send the simple cross-origin POST (to the witness, which accepts it) ...
    EXPECT_EQ(witnessed.load(), 1) << results.dump();
    EXPECT_EQ(results["witness"], "opaque") << results.dump();
    // ... and the JSON one failed its preflight.
    EXPECT_NE(results["snapshot_json"].get<std::string>().find("blocked"), std::string::npos)
        << results.dump();
    // No snapshot was written by any of the three (simple, form, preflighted JSON).
    EXPECT_TRUE(std::filesystem::is_empty(options.snapshot_dir)) << results.dump();
    EXPECT_NE(results["json"].get<std::string>().find("blocked"), std::string::npos)
        << results.dump();

    std::this_thread::sleep_for(
        500ms);  // a capture, had one started, would have created the session by now
    EXPECT_FALSE(std::filesystem::exists(session)) << results.dump();
    httplib::Client client("127.0.0.1", live.server.port());
    const auto status = client.Get("/api/status");
    ASSERT_TRUE(status);
    const auto j = nlohmann::json::parse(status->body);
    EXPECT_EQ(j["capture"]["phase"], "idle") << j.dump();
    EXPECT_EQ(j["capture"]["steps_recorded"], 0) << j.dump();
    const auto observations = client.Get("/api/observations");
    ASSERT_TRUE(observations);
    EXPECT_EQ(nlohmann::json::parse(observations->body), nlohmann::json::object());
}

}  // namespace
}  // namespace tirpol::live
