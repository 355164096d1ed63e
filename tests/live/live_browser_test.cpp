// Requires TIRPOL_WITH_ARAVIS (built only with that back end: cmake/TirpolBackends.cmake).
// End to end, as an operator uses it: the real `tirpol live` executable with Aravis's fake GigE
// Vision camera (arv-fake-gv-camera-0.8, 640×512 Mono16 at 30 fps) and the APT stage simulator on a
// pseudo-terminal, and headless Chromium as the browser. The page runs in its test mode
// (?observe=ID): it posts what it shows (frames drawn, last frame id, painted fraction of the S0
// and DoLP canvases, capture state) to /api/observations, which the test reads, and drives the
// capture buttons from URL parameters. Screenshots go to build/test-artefacts/live/. A missing
// chromium or aravis-tools fails these tests: they never skip.

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "access.h"
#include "child_process.h"
#include "fake_gv_camera_process.h"
#include "find_on_path.h"
#include "httplib_after_eigen.h"
#include "png_text.h"
#include "test_support.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/session.h"

namespace tirpol::live {
namespace {

using namespace std::chrono_literals;
using nlohmann::json;

constexpr const char* kCameraUri =
    "aravis://127.0.0.1?pixel_format=Mono16&width=640&height=512&fps=30";

using test::find_on_path;

std::string read_text(const std::filesystem::path& path) {
    std::ifstream in(path);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class LiveEndToEnd : public ::testing::Test {
protected:
    void SetUp() override {
        const auto chromium_path = find_on_path("chromium");
        ASSERT_TRUE(chromium_path)
            << "chromium is not on PATH (Debian package chromium): the live-view tests need it";
        m_chromium = *chromium_path;
        const auto fake = test::find_fake_gv_camera_binary();
        ASSERT_TRUE(fake) << test::kFakeGvCameraBinary
                          << " is not on PATH (Debian package aravis-tools)";
        m_lock = std::make_unique<test::LoopbackGigELock>();
        m_camera = std::make_unique<test::FakeGvCameraProcess>(*fake, std::vector<std::string>{});
        ASSERT_TRUE(m_camera->ready()) << "the fake GigE Vision camera did not start";
        std::filesystem::create_directories(TIRPOL_ARTEFACT_DIR);
    }

    std::filesystem::path dir() const { return m_dir.path(); }

    void start_stage(const char* deg_per_s) {
        m_stage = std::make_unique<test::ChildProcess>(
            std::vector<std::string>{TIRPOL_STAGE_SIM_PATH, "--protocol", "apt", "--link",
                                     (dir() / "stage").string(), "--move-deg-per-s", deg_per_s},
            dir() / "stage-sim.log");
        for (int i = 0; i < 500 && !std::filesystem::exists(dir() / "stage"); ++i)
            std::this_thread::sleep_for(10ms);
        ASSERT_TRUE(std::filesystem::exists(dir() / "stage")) << read_text(dir() / "stage-sim.log");
    }
    std::string stage_uri() const { return "thorlabs-apt://" + (dir() / "stage").string(); }

    /// Starts `tirpol live` and reads the port (and token) it prints.
    void start_live(std::vector<std::string> extra, const std::string& camera = kCameraUri) {
        std::vector<std::string> args{TIRPOL_CLI_PATH, "live", "--camera", camera, "--port", "0"};
        args.insert(args.end(), extra.begin(), extra.end());
        m_live = std::make_unique<test::ChildProcess>(args, dir() / "live.log");
        const std::regex printed(R"(open http://[^:]+:(\d+)/(\?token=([0-9a-f]+))?)");
        for (int i = 0; i < 600; ++i) {
            std::smatch m;
            const std::string log = read_text(dir() / "live.log");
            if (std::regex_search(log, m, printed)) {
                m_port = std::stoi(m[1]);
                m_token = m[3];
                return;
            }
            ASSERT_TRUE(m_live->running()) << "tirpol live exited: " << log;
            std::this_thread::sleep_for(50ms);
        }
        FAIL() << "tirpol live printed no address in 30 s: " << read_text(dir() / "live.log");
    }

    std::string page_url(const std::string& query) const {
        std::string url = "http://127.0.0.1:" + std::to_string(m_port) + "/?" + query;
        if (!m_token.empty()) url += "&token=" + m_token;
        return url;
    }

    /// A headless Chromium showing the page until the test ends.
    void open_browser(const std::string& name, const std::string& query) {
        const auto profile = dir() / ("chromium-" + name);
        m_browsers.push_back(std::make_unique<test::ChildProcess>(
            std::vector<std::string>{m_chromium.string(), "--headless", "--no-sandbox",
                                     "--disable-gpu", "--no-first-run",
                                     "--user-data-dir=" + profile.string(),
                                     "--window-size=1400,1300", page_url(query)},
            dir() / ("chromium-" + name + ".log")));
    }

    /// A screenshot by a fresh browser, as docs/live.md says to take one (no `?still=1`): headless,
    /// the page stops polling once it has drawn frames (and a Stokes cycle, with a stage), then
    /// the virtual time budget runs out.
    void screenshot(const std::string& file, const std::string& query) {
        const auto out = std::filesystem::path(TIRPOL_ARTEFACT_DIR) / file;
        std::filesystem::remove(out);
        test::ChildProcess shot(
            {m_chromium.string(), "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
             "--user-data-dir=" + (dir() / "chromium-shot").string(), "--hide-scrollbars",
             "--window-size=1100,950", "--virtual-time-budget=20000",
             "--screenshot=" + out.string(), page_url(query)},
            dir() / "chromium-shot.log");
        ASSERT_TRUE(shot.wait_for(120s).has_value()) << "chromium --screenshot did not finish";
        ASSERT_TRUE(std::filesystem::exists(out)) << read_text(dir() / "chromium-shot.log");
        EXPECT_GT(std::filesystem::file_size(out), 20000u) << "a blank screenshot";
    }

    json observations() const {
        httplib::Client client("127.0.0.1", m_port);
        httplib::Headers headers;
        if (!m_token.empty()) headers.emplace("X-Tirpol-Token", m_token);
        const auto r = client.Get("/api/observations", headers);
        if (!r || r->status != 200) return json::object();
        return json::parse(r->body);
    }

    /// Waits until `ok(observations)` holds; the last observations otherwise (for the failure
    /// message).
    bool wait_for_observations(const std::function<bool(const json&)>& ok,
                               std::chrono::seconds timeout, json& last) {
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        while (std::chrono::steady_clock::now() < deadline) {
            last = observations();
            if (ok(last)) return true;
            std::this_thread::sleep_for(200ms);
        }
        return false;
    }

    int stop_live() {
        m_live->signal(SIGTERM);
        const auto code = m_live->wait_for(30s);
        return code ? *code : -1;
    }

    test::TempDir m_dir{"tirpol-live-e2e"};
    std::filesystem::path m_chromium;
    std::unique_ptr<test::LoopbackGigELock> m_lock;
    std::unique_ptr<test::FakeGvCameraProcess> m_camera;
    std::unique_ptr<test::ChildProcess> m_stage, m_live;
    std::vector<std::unique_ptr<test::ChildProcess>> m_browsers;
    int m_port = 0;
    std::string m_token;
};

bool shows_frames(const json& obs, const std::string& client, int frames) {
    return obs.contains(client) && obs[client]["frames_shown"].get<int>() >= frames &&
           obs[client]["s0_painted"].get<double>() > 0.5;
}

TEST_F(LiveEndToEnd, TwoBrowsersShowLiveS0AndTheFrameCounterAdvances) {
    start_live({});
    open_browser("a", "observe=a&mouse=1");
    // Page b locks the S0 span and picks the grey palette from its address (the same controls as
    // the page's selects).
    open_browser("b", "observe=b&palette=grey&span=1000,3000");
    json obs;
    ASSERT_TRUE(wait_for_observations(
        [](const json& o) { return shows_frames(o, "a", 3) && shows_frames(o, "b", 3); }, 90s, obs))
        << obs.dump(1) << read_text(dir() / "live.log");
    const json first = obs;
    // Both pages keep drawing newer frames (the fake camera's ids wrap 65535 → 1, hence
    // "different").
    ASSERT_TRUE(wait_for_observations(
        [&](const json& o) {
            for (const char* c : {"a", "b"})
                if (o[c]["frames_shown"].get<int>() < first[c]["frames_shown"].get<int>() + 10 ||
                    o[c]["last_frame_id"] == first[c]["last_frame_id"])
                    return false;
            return true;
        },
        90s, obs))
        << obs.dump(1);
    EXPECT_EQ(obs["a"]["colorbar_units"], "counts");
    EXPECT_FALSE(obs["a"]["center_readout"].empty());  // the cursor readout of the middle pixel
    // Page a dragged a 40×40 region from pixel (100, 80) and zoomed once with the wheel (mouse=1).
    const json& mouse = obs["a"]["mouse"];
    ASSERT_TRUE(mouse.is_object()) << obs["a"].dump(1);
    EXPECT_EQ(mouse["region"][0], "x 100–139, y 80–119 (1600 px)");
    EXPECT_NE(mouse["region"][1].get<std::string>().find("live  S0    mean"), std::string::npos)
        << mouse.dump(1);
    EXPECT_NE(mouse["region"][1].get<std::string>().find("(1600 px)"), std::string::npos)
        << mouse.dump(1);
    EXPECT_EQ(mouse["cursor"][0], "x 139, y 119");
    EXPECT_DOUBLE_EQ(mouse["zoom"].get<double>(), 1.25);
    // The region readout comes from the server (GET /api/region) for the region dragged.
    const json& readout = obs["a"]["region_readout"];
    ASSERT_TRUE(readout.is_object()) << obs["a"].dump(1);
    EXPECT_EQ(readout["region"], json::array({100, 80, 139, 119}));
    EXPECT_EQ(readout["live"]["S0"]["count"], 1600);
    // Focus: one gradient-energy sample per frame drawn, of the moving test ramp (non-zero).
    EXPECT_GE(obs["a"]["focus"]["n"].get<int>(), 3) << obs["a"].dump(1);
    EXPECT_GT(obs["a"]["focus"]["last"].get<double>(), 0.0);
    EXPECT_EQ(readout["focus"]["units"], "(counts/px)²");
    // Page b: the locked span is the colour bar's, drawn in grey; page a keeps inferno and auto.
    EXPECT_EQ(obs["b"]["colorbars"]["colorbar"]["range"], json::array({1000, 3000}))
        << obs["b"].dump(1);
    EXPECT_EQ(obs["b"]["colorbars"]["colorbar"]["units"], "counts");
    EXPECT_TRUE(obs["b"]["s0_grey"].get<bool>());
    EXPECT_FALSE(obs["a"]["s0_grey"].get<bool>());
    EXPECT_NE(obs["a"]["colorbars"]["colorbar"]["range"], json::array({1000, 3000}));
    screenshot("live_s0.png", "");
    EXPECT_EQ(stop_live(), 0) << read_text(dir() / "live.log");
}

TEST_F(LiveEndToEnd, WithAStageDoLPAppearsAndACaptureFromThePageWritesACompleteSession) {
    start_stage("360");
    test::write_text(dir() / "plan.yaml", "frames_per_angle: 4\nsettle_s: 0.1\n");
    start_live({"--stage", stage_uri(), "--frames-per-angle", "2", "--settle-s", "0.1"});
    const auto session = dir() / "session";
    open_browser("s", "observe=s&mouse=1&dolp_min=0&capture_plan=" +
                          (dir() / "plan.yaml").string() + "&capture_output=" + session.string());
    // Page m masks AoP wherever DoLP < 1, i.e. (nearly) everywhere; it keeps the default
    // palettes. Page c picks the other S1/S2 and AoP palettes from its address (the page's
    // selects).
    open_browser("m", "observe=m&dolp_min=1");
    open_browser("c", "observe=c&palette_signed=coolwarm&palette_aop=twilight");
    json obs;
    ASSERT_TRUE(wait_for_observations(
        [](const json& o) {
            return o.contains("s") && o["s"]["capture"].is_object() &&
                   o["s"]["capture"]["phase"] == "complete" &&
                   o["s"]["stokes_shown"].get<int>() >= 1 &&
                   o["s"]["dolp_painted"].get<double>() > 0.5 && o.contains("m") &&
                   o["m"]["aop_masked"].is_number() && o["s"]["region_readout"].is_object() &&
                   o["s"]["region_readout"].contains("cycle");
        },
        180s, obs))
        << obs.dump(1) << read_text(dir() / "live.log");
    // The AoP mask: none at threshold 0 (every finite DoLP is ≥ 0), nearly all at 1.
    EXPECT_LT(obs["s"]["aop_masked"].get<double>(), 0.05) << obs["s"].dump(1);
    EXPECT_GT(obs["m"]["aop_masked"].get<double>(), 0.9) << obs["m"].dump(1);
    // A colour bar with units under every image; DoLP from 0, AoP over 0–180°, S1/S2 about 0.
    const json& bars = obs["s"]["colorbars"];
    for (const char* name : {"colorbar", "cb-S0", "cb-S1", "cb-S2", "cb-DoLP", "cb-AoP"})
        EXPECT_TRUE(bars.contains(name)) << name << " " << bars.dump(1);
    EXPECT_EQ(bars["cb-DoLP"]["range"][0], 0);
    EXPECT_EQ(bars["cb-AoP"]["range"], json::array({0, 180}));
    EXPECT_EQ(bars["cb-AoP"]["units"], "deg");
    EXPECT_EQ(bars["cb-S1"]["units"], "counts");
    EXPECT_DOUBLE_EQ(bars["cb-S1"]["range"][0].get<double>(),
                     -bars["cb-S1"]["range"][1].get<double>());
    // The region readout's AoP: circular statistics over the dragged 40×40 pixels.
    const json& aop = obs["s"]["region_readout"]["cycle"]["AoP"];
    EXPECT_TRUE(aop["circular"].get<bool>()) << aop.dump();
    EXPECT_LE(aop["count"].get<int>() + aop["masked"].get<int>(), 1600);
    if (aop["mean"].is_number()) {
        EXPECT_GE(aop["mean"].get<double>(), 0.0);
        EXPECT_LT(aop["mean"].get<double>(), 180.0);
    }
    // DoLP is a fraction: its range lies in [0, 1] (the realizable projection of reduce_stokes).
    EXPECT_GE(obs["s"]["dolp_range"][0].get<double>(), 0.0);
    EXPECT_LE(obs["s"]["dolp_range"][1].get<double>(), 1.0);
    EXPECT_TRUE(obs["s"]["stage"]["angle_deg"].is_number());
    const SessionManifest m = read_session(session);
    EXPECT_TRUE(m.complete);
    ASSERT_EQ(m.records.size(), 4u);
    EXPECT_EQ(m.camera.width, 640);
    EXPECT_EQ(m.camera.pixel_format, "Mono16");
    for (const auto& r : m.records) EXPECT_EQ(r.frames, 4);
    screenshot("live_stokes.png", "");
    EXPECT_EQ(stop_live(), 0) << read_text(dir() / "live.log");
}

// Palettes of the Stokes images chosen on the page, with the simulated camera (uniform,
// unpolarized, with noise: S1 is noise about 0) behind the simulated stage. Page m keeps the
// default palettes, page c picks the others from its address (the same selects an operator uses).
TEST_F(LiveEndToEnd, S1ZeroIsThePalettesCentreColourInEachPaletteChosenOnThePage) {
    start_live({"--stage", "sim://", "--frames-per-angle", "2", "--settle-s", "0"},
               "sim://uniform?width=64&height=48&counts=1500&noise=3&fps=30");
    open_browser("m", "observe=m");
    open_browser("c", "observe=c&palette_signed=coolwarm&palette_aop=twilight");
    json obs;
    ASSERT_TRUE(wait_for_observations(
        [](const json& o) {
            return o.contains("m") && o.contains("c") && o["m"]["palettes"].is_object() &&
                   o["c"]["palettes"].is_object();
        },
        120s, obs))
        << obs.dump(1) << read_text(dir() / "live.log");
    // S1's zero is painted in the diverging palette's centre colour: ColorBrewer RdBu's #f7f7f7
    // (colorbrewer2.org, 5 classes) by default, Moreland's cool-warm (221, 221, 221)
    // (SAND2009-0000) when chosen. The pixel nearest 0 must lie within half a palette step (1/512
    // of the symmetric range) for its colour to be the centre's.
    const std::map<std::string, json> centre{{"m", json::array({247, 247, 247})},
                                             {"c", json::array({221, 221, 221})}};
    for (const auto& [page, colour] : centre) {
        const json& p = obs[page]["palettes"];
        ASSERT_TRUE(p["s1_zero"].is_object()) << p.dump(1);
        const double half_range = p["s1_range"][1].get<double>();
        EXPECT_DOUBLE_EQ(p["s1_range"][0].get<double>(), -half_range);
        EXPECT_LE(std::abs(p["s1_zero"]["value"].get<double>()), half_range / 512.0) << p.dump(1);
        EXPECT_EQ(p["s1_zero"]["rgb"], colour) << page << ": " << p.dump(1);
        // A cyclic AoP palette: 0° and 180° (the same axis) have one colour.
        EXPECT_EQ(p["aop_bar_ends"][0], p["aop_bar_ends"][1]) << page << ": " << p.dump(1);
    }
    EXPECT_EQ(obs["c"]["palettes"]["s1_palette"], "coolwarm");
    EXPECT_EQ(obs["c"]["palettes"]["aop_palette"], "twilight");
    EXPECT_EQ(obs["m"]["palettes"]["s1_palette"], "rdbu");
    EXPECT_NE(obs["c"]["palettes"]["aop_bar_ends"][0], obs["m"]["palettes"]["aop_bar_ends"][0]);
    EXPECT_EQ(stop_live(), 0) << read_text(dir() / "live.log");
}

// The page's Snapshot button with the simulated camera (uniform 1500 counts, noise 3) behind the
// simulated stage: the EXR holds the cycle's float Stokes and the live frame, with the metadata;
// each PNG quick look carries the same metadata in its text chunks.
TEST_F(LiveEndToEnd, ASnapshotFromThePageWritesFloatStokesAndQuickLooksWithMetadata) {
    const auto snaps = dir() / "snaps";
    start_live({"--stage", "sim://", "--frames-per-angle", "2", "--settle-s", "0", "--snapshot-dir",
                snaps.string()},
               "sim://uniform?width=64&height=48&counts=1500&noise=3&fps=30");
    open_browser("n", "observe=n&snapshot=1");
    json obs;
    ASSERT_TRUE(wait_for_observations(
        [](const json& o) { return o.contains("n") && o["n"]["snapshot"].is_object(); }, 120s, obs))
        << obs.dump(1) << read_text(dir() / "live.log");
    const json& answer = obs["n"]["snapshot"];
    ASSERT_TRUE(answer.contains("files")) << answer.dump(1);
    ASSERT_EQ(answer["files"].size(), 7u) << answer.dump(1);  // the EXR, PNGs of 5 + live_S0
    const Image image = read_exr(snaps / answer["files"][0].get<std::string>());
    ASSERT_EQ(image.width(), 64);
    ASSERT_EQ(image.height(), 48);
    for (const char* name : {"S0", "S1", "S2", "DoLP", "AoP", "live_S0"})
        ASSERT_TRUE(image.has_channel(name)) << name;
    // The values: a uniform unpolarized 1500 counts; floats, not the page's 16-bit display codes.
    const auto mean = [&](const char* name) { return channel_stats(image.channel(name)).mean; };
    // Each angle reads 1500 counts; an ideal analyzer passes I = (S0 + S1 cos 2θ + S2 sin 2θ)/2.
    EXPECT_NEAR(mean("S0"), 3000.0, 1.0);
    EXPECT_NEAR(mean("live_S0"), 1500.0, 1.0);
    EXPECT_NEAR(mean("S1"), 0.0, 1.0);
    EXPECT_NEAR(mean("S2"), 0.0, 1.0);
    for (const float v : image.channel("live_S0")) EXPECT_EQ(v, std::round(v));  // raw counts
    std::size_t checked = 0;
    for (std::size_t i = 0; i < image.pixel_count(); ++i) {
        const double s0 = image.channel("S0")[i], s1 = image.channel("S1")[i],
                     s2 = image.channel("S2")[i];
        const double dolp = std::hypot(s1, s2) / s0;
        if (dolp < 1e-4) continue;
        EXPECT_NEAR(image.channel("DoLP")[i], dolp, 1e-5) << i;
        const double aop = std::fmod(std::atan2(s2, s1) * 90.0 / M_PI + 180.0, 180.0);
        const double d = std::abs(image.channel("AoP")[i] - aop);
        EXPECT_LT(std::min(d, 180.0 - d), 1e-2) << i;
        ++checked;
    }
    EXPECT_GT(checked, image.pixel_count() / 2);
    // The metadata: time, analyzer angles read back from the stage, camera, frame ids.
    const auto& a = image.attributes();
    const auto text = [&](const char* key) { return std::get<std::string>(a.at(key)); };
    EXPECT_EQ(text("time_utc"), answer["time_utc"]);
    EXPECT_EQ(text("camera_uri").rfind("sim://uniform", 0), 0u) << text("camera_uri");
    EXPECT_EQ(text("frame_id"), std::to_string(answer["frame_id"].get<std::uint64_t>()));
    EXPECT_EQ(text("units"), "counts");
    const auto angles = std::get<std::vector<double>>(a.at("analyzer_angles_deg"));
    ASSERT_EQ(angles.size(), 4u);
    for (std::size_t k = 0; k < 4; ++k) EXPECT_NEAR(angles[k], 45.0 * k, 1.0);
    const auto ids = std::get<std::vector<double>>(a.at("cycle_frame_ids"));
    ASSERT_EQ(ids.size(), 8u);  // first and last frame averaged at each angle
    EXPECT_TRUE(std::is_sorted(ids.begin(), ids.end()));
    EXPECT_LE(ids.back(), answer["frame_id"].get<double>());
    for (std::size_t k = 1; k < answer["files"].size(); ++k) {
        const auto png = snaps / answer["files"][k].get<std::string>();
        const auto chunks = test::png_text_chunks(png);
        EXPECT_EQ(chunks.at("tirpol.time_utc"), text("time_utc")) << png;
        EXPECT_EQ(chunks.at("Creation Time"), text("time_utc")) << png;
        EXPECT_EQ(chunks.at("tirpol.camera_uri"), text("camera_uri")) << png;
        EXPECT_EQ(chunks.at("tirpol.frame_id"), text("frame_id")) << png;
        EXPECT_EQ(chunks.at("tirpol.analyzer_angles_deg"),
                  fmt::format("{}", fmt::join(angles, ",")))
            << png;
    }
    EXPECT_EQ(stop_live(), 0) << read_text(dir() / "live.log");

    // The output guard at start: a file the snapshots would claim, which no tirpol command wrote
    // there, is refused (exit 2, naming the option) unless --force.
    const auto other = dir() / "other";
    std::filesystem::create_directories(other);
    test::write_text(other / "snapshot-mine.exr", "not ours");
    test::ChildProcess refused(
        {TIRPOL_CLI_PATH, "live", "--camera", "sim://uniform?width=8&height=8", "--port", "0",
         "--snapshot-dir", other.string()},
        dir() / "refused.log");
    const auto code = refused.wait_for(30s);
    ASSERT_TRUE(code.has_value());
    EXPECT_EQ(*code, 2) << read_text(dir() / "refused.log");
    EXPECT_NE(read_text(dir() / "refused.log").find("--snapshot-dir"), std::string::npos)
        << read_text(dir() / "refused.log");
    EXPECT_EQ(read_text(other / "snapshot-mine.exr"), "not ours");
}

// A microgrid (division-of-focal-plane) camera without a stage: Aravis's fake camera streaming
// Mono16 declared as the Sony layout (microgrid=sony: (0,0) = 90°, (0,1) = 45°, (1,0) = 135°,
// (1,1) = 0°). Every frame is demosaiced (bilinear) and reduced on its own; a snapshot stores the
// frame (live_S0) beside its Stokes images, which the test recomputes from the raw pixels.
TEST_F(LiveEndToEnd, AMicrogridCameraShowsStokesFromSingleFramesWithoutAStage) {
    const auto snaps = dir() / "snaps";
    start_live({"--snapshot-dir", snaps.string(), "--demosaic", "bilinear"},
               std::string(kCameraUri) + "&microgrid=sony");
    open_browser("d", "observe=d&dolp_min=0&snapshot=1");
    json obs;
    ASSERT_TRUE(wait_for_observations(
        [](const json& o) {
            return o.contains("d") && o["d"]["stokes_shown"].get<int>() >= 5 &&
                   o["d"]["dolp_painted"].get<double>() > 0.5 && o["d"]["snapshot"].is_object();
        },
        120s, obs))
        << obs.dump(1) << read_text(dir() / "live.log");
    EXPECT_TRUE(obs["d"]["stage"].is_null()) << obs["d"].dump(1);
    for (const char* name : {"cb-S0", "cb-S1", "cb-S2", "cb-DoLP", "cb-AoP"})
        EXPECT_TRUE(obs["d"]["colorbars"].contains(name)) << name;
    const json& answer = obs["d"]["snapshot"];
    ASSERT_TRUE(answer.contains("files")) << answer.dump(1);
    const Image image = read_exr(snaps / answer["files"][0].get<std::string>());
    ASSERT_EQ(image.width(), 640);
    ASSERT_EQ(image.height(), 512);
    const auto& a = image.attributes();
    EXPECT_EQ(std::get<std::string>(a.at("microgrid_frame_id")),
              std::get<std::string>(a.at("frame_id")));  // the Stokes of the stored frame
    EXPECT_EQ(std::get<std::string>(a.at("demosaic_method")), "bilinear");
    EXPECT_EQ(std::get<std::string>(a.at("microgrid_pattern")), "90,45,135,0");
    // At a 0° pixel (odd x, odd y) of the Sony layout, bilinear interpolation (Ratliff et al.
    // 2009) takes 90° from the 4 diagonal neighbours, 45° from the 2 vertical and 135° from the 2
    // horizontal ones; an ideal analyzer then gives S0 = (I0 + I45 + I90 + I135)/2,
    // S1 = I0 − I90, S2 = I45 − I135 (docs/conventions.md). Where the fake camera's ramp wraps
    // (65535 → 0) inside a cell the interpolated vector is unrealizable (√(S1² + S2²) > S0), and
    // the reduction projects it onto the cone (ReductionOptions::project_to_realizable): S1 and S2
    // scaled by S0/√(S1² + S2²). Whether a snapshot's frame has such cells depends on its phase.
    const auto& raw = image.channel("live_S0");
    const auto at = [&](int x, int y) { return static_cast<double>(raw[image.index(x, y)]); };
    int checked = 0, projected = 0;
    for (int y = 1; y + 1 < image.height(); y += 2)
        for (int x = 1; x + 1 < image.width(); x += 2) {
            const double i0 = at(x, y),
                         i90 = (at(x - 1, y - 1) + at(x + 1, y - 1) + at(x - 1, y + 1) +
                                at(x + 1, y + 1)) /
                               4.0,
                         i45 = (at(x, y - 1) + at(x, y + 1)) / 2.0,
                         i135 = (at(x - 1, y) + at(x + 1, y)) / 2.0;
            const std::size_t i = image.index(x, y);
            const double s0 = (i0 + i45 + i90 + i135) / 2.0, s1 = i0 - i90, s2 = i45 - i135,
                         polarized = std::hypot(s1, s2),
                         scale = polarized > s0 && s0 >= 0.0 ? s0 / polarized : 1.0;
            ASSERT_NEAR(image.channel("S0")[i], s0, 0.1) << x << "," << y;
            ASSERT_NEAR(image.channel("S1")[i], scale * s1, 0.1) << x << "," << y;
            ASSERT_NEAR(image.channel("S2")[i], scale * s2, 0.1) << x << "," << y;
            ++checked;
            projected += scale < 1.0;
        }
    EXPECT_EQ(checked, 319 * 255);
    EXPECT_LT(projected, checked / 10) << "cells projected onto the realizable cone";
    screenshot("live_microgrid.png", "");
    EXPECT_EQ(stop_live(), 0) << read_text(dir() / "live.log");
}

// Recording from the page with the simulated camera (uniform 1500 counts, noise 3) and the
// simulated stage: the plan drives the stage, the session is the one `tirpol acquire` writes
// (core's reader checks every frame against the manifest), and its frames give the source's Stokes
// through an ideal analyzer: S0 = 3000 counts (each angle reads S0/2), S1 = S2 = 0 within noise.
TEST_F(LiveEndToEnd, ARecordingFromThePageWithTheSimulatedRigIsASessionThatReduces) {
    test::write_text(dir() / "plan.yaml", "frames_per_angle: 4\nsettle_s: 0\n");
    start_live({"--stage", "sim://", "--frames-per-angle", "1", "--settle-s", "0"},
               "sim://uniform?width=64&height=48&counts=1500&noise=3&fps=30");
    const auto session = dir() / "session";
    open_browser("r", "observe=r&capture_plan=" + (dir() / "plan.yaml").string() +
                          "&capture_output=" + session.string());
    json obs;
    ASSERT_TRUE(wait_for_observations(
        [](const json& o) {
            return o.contains("r") && o["r"]["capture"].is_object() &&
                   o["r"]["capture"]["phase"] == "complete";
        },
        120s, obs))
        << obs.dump(1) << read_text(dir() / "live.log");
    EXPECT_TRUE(obs["r"]["clicked_start"].get<bool>());
    const SessionManifest m = read_session(session);
    EXPECT_TRUE(m.complete);
    ASSERT_EQ(m.records.size(), 4u);
    EXPECT_EQ(m.camera.width, 64);
    std::vector<double> means;  // at 0, 45, 90, 135°
    for (std::size_t k = 0; k < m.records.size(); ++k) {
        const SessionRecord& r = m.records[k];
        EXPECT_EQ(r.frames, 4);
        EXPECT_NEAR(r.angle_deg_measured, 45.0 * static_cast<double>(k), 0.5);
        const Image frame = read_session_frame(session, m, r);
        means.push_back(channel_stats(frame.channel("counts")).mean);
        EXPECT_NEAR(means.back(), 1500.0, 1.0) << r.file;
    }
    // Ideal analyzer at 0/45/90/135° (docs/conventions.md): S0 = ΣI/2, S1 = I0 − I90,
    // S2 = I45 − I135.
    EXPECT_NEAR((means[0] + means[1] + means[2] + means[3]) / 2.0, 3000.0, 1.0);
    EXPECT_NEAR(means[0] - means[2], 0.0, 0.5);
    EXPECT_NEAR(means[1] - means[3], 0.0, 0.5);
    EXPECT_EQ(stop_live(), 0) << read_text(dir() / "live.log");
}

TEST_F(LiveEndToEnd, ACaptureStoppedFromThePageResumesWithTirpolAcquire) {
    start_stage("30");  // 45° moves take 1.5 s: the page's Stop lands during the plan
    test::write_text(dir() / "plan.yaml", "frames_per_angle: 4\nsettle_s: 0.1\n");
    start_live({"--stage", stage_uri()});
    const auto session = dir() / "session";
    open_browser("r", "observe=r&capture_stop_after=1&capture_plan=" +
                          (dir() / "plan.yaml").string() + "&capture_output=" + session.string());
    json obs;
    ASSERT_TRUE(wait_for_observations(
        [](const json& o) {
            return o.contains("r") && o["r"]["capture"].is_object() &&
                   o["r"]["capture"]["phase"] == "stopped";
        },
        180s, obs))
        << obs.dump(1) << read_text(dir() / "live.log");
    EXPECT_TRUE(obs["r"]["clicked_stop"].get<bool>());
    const SessionManifest partial = read_session(session);
    EXPECT_FALSE(partial.complete);
    ASSERT_GE(partial.records.size(), 1u);
    ASSERT_LT(partial.records.size(), 4u);
    EXPECT_EQ(stop_live(), 0) << read_text(dir() / "live.log");

    // The same session, continued by `tirpol acquire --resume` on the same devices.
    test::ChildProcess acquire(
        {TIRPOL_CLI_PATH, "acquire", (dir() / "plan.yaml").string(), "--camera", kCameraUri,
         "--stage", stage_uri(), "-o", session.string(), "--resume", "--non-interactive"},
        dir() / "acquire.log");
    const auto code = acquire.wait_for(180s);
    ASSERT_TRUE(code.has_value());
    ASSERT_EQ(*code, 0) << read_text(dir() / "acquire.log");
    const SessionManifest m = read_session(session);
    EXPECT_TRUE(m.complete);
    ASSERT_EQ(m.records.size(), 4u);
    for (std::size_t i = 0; i < partial.records.size(); ++i)
        EXPECT_EQ(m.records[i], partial.records[i]);
}

// The digital twin's renderer-backed camera behind the in-process simulated stage, as a user tries
// `tirpol live` without hardware: config/scenes/panels_before_trees.yaml at 80×64, 2 samples per
// pixel. Its middle quarter (three painted panels tilted 30° on asphalt seen at a grazing angle)
// is partially polarized, so the page shows DoLP that is not noise. (At this geometry most of it
// comes from the ground; the panels' own DoLP is within the per-pixel noise at 2 spp — see
// build/test-artefacts/live/live_scene.png.)
TEST_F(LiveEndToEnd, TheSceneCameraBehindASimulatedStageShowsPolarization) {
    const std::string scene =
        std::filesystem::path(TIRPOL_SOURCE_DIR) / "config/scenes/panels_before_trees.yaml";
    start_live({"--stage", "sim://", "--frames-per-angle", "2", "--settle-s", "0"},
               "sim://" + scene + "?width=80&height=64&spp=2&fps=10");
    open_browser("p", "observe=p&dolp_min=0");
    json obs;
    ASSERT_TRUE(wait_for_observations(
        [](const json& o) {
            return o.contains("p") && o["p"]["stokes_shown"].get<int>() >= 2 &&
                   o["p"]["dolp_painted"].get<double>() > 0.5;
        },
        240s, obs))
        << obs.dump(1) << read_text(dir() / "live.log");
    // The server's readout over the middle quarter (the page's default focus region): its mean S1,
    // S2 differ from 0 by far more than their standard errors (each pixel alone is noisy at 2
    // samples per pixel), and DoLP is drawn from 0.
    const json& cycle = obs["p"]["region_readout"]["cycle"];
    ASSERT_TRUE(cycle.is_object()) << obs["p"].dump(1);
    const double n = cycle["S1"]["count"].get<double>();
    ASSERT_GT(n, 100.0);
    const double s1 = cycle["S1"]["mean"], s2 = cycle["S2"]["mean"];
    const double sd1 = cycle["S1"]["std"], sd2 = cycle["S2"]["std"];
    const double polarized = std::hypot(s1, s2),
                 standard_error = std::hypot(sd1, sd2) / std::sqrt(n);
    EXPECT_GT(polarized, 5.0 * standard_error) << cycle.dump(1);
    EXPECT_GT(polarized / cycle["S0"]["mean"].get<double>(), 1e-3) << cycle.dump(1);
    EXPECT_GT(obs["p"]["dolp_range"][1].get<double>(), 0.0);
    EXPECT_EQ(obs["p"]["colorbars"]["cb-DoLP"]["range"][0], 0);
    screenshot("live_scene.png", "");
    EXPECT_EQ(stop_live(), 0) << read_text(dir() / "live.log");
}

TEST_F(LiveEndToEnd, BeyondLoopbackOnlyRequestsWithTheTokenAreServed) {
    start_live({"--bind", "0.0.0.0"});
    ASSERT_EQ(m_token.size(), 32u) << read_text(dir() / "live.log");
    // What the operator opens from a tablet: this machine's network addresses, never 0.0.0.0.
    const std::string printed = read_text(dir() / "live.log");
    EXPECT_EQ(printed.find("http://0.0.0.0"), std::string::npos) << printed;
    const std::vector<std::string> own = interface_addresses();
    const std::regex printed_url(R"(http://\[?([0-9A-Fa-f.:]+?)\]?:\d+/\?token=)");
    int urls = 0;
    for (auto it = std::sregex_iterator(printed.begin(), printed.end(), printed_url);
         it != std::sregex_iterator(); ++it, ++urls) {
        const std::string host = (*it)[1];
        EXPECT_TRUE(host == "127.0.0.1" || std::find(own.begin(), own.end(), host) != own.end())
            << host << " is not an address of this machine";
    }
    EXPECT_GE(urls, 1) << printed;
    httplib::Client client("127.0.0.1", m_port);
    auto refused = client.Get("/");
    ASSERT_TRUE(refused);
    EXPECT_EQ(refused->status, 401);
    EXPECT_EQ(client.Get("/api/frame?after=0")->status, 401);
    open_browser("t", "observe=t");  // page_url adds the token
    // A second browser without the token: its page is refused, so it can never report.
    m_browsers.push_back(std::make_unique<test::ChildProcess>(
        std::vector<std::string>{m_chromium.string(), "--headless", "--no-sandbox", "--disable-gpu",
                                 "--user-data-dir=" + (dir() / "chromium-n").string(),
                                 "http://127.0.0.1:" + std::to_string(m_port) + "/?observe=n"},
        dir() / "chromium-n.log"));
    json obs;
    ASSERT_TRUE(
        wait_for_observations([](const json& o) { return shows_frames(o, "t", 3); }, 90s, obs))
        << obs.dump(1);
    std::this_thread::sleep_for(2s);
    EXPECT_FALSE(observations().contains("n"));
    EXPECT_EQ(stop_live(), 0) << read_text(dir() / "live.log");
}

}  // namespace
}  // namespace tirpol::live
