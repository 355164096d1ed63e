// Session store (schema tirpol.session v3, v1 and v2 still read; docs/session-format.md): round
// trips, atomic creation, crash recovery, no-overwrite guarantees and the reader's error messages
// for damaged sessions.

#include "tirpol/core/session.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <csignal>

#include "test_support.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"

namespace tirpol {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;

SessionManifest example_manifest() {
    SessionManifest m;
    m.camera = {"sim://panel",
                "tirpol",
                "SimCam",
                "0001",
                "Mono16",
                8,
                4,
                16,
                30.0,
                {{"R", 16556.0}, {"B", 1428.0}}};
    m.stage = {"sim://", "tirpol", "SimStage", "S1", "1.0", 409600.0 / 3.0};
    m.plan = json{{"angles_deg", {0, 45, 90, 135}}, {"frames_per_angle", 4}};
    m.metadata = json{{"site", "roof"}, {"operator", "test"}};
    return m;
}

Image example_frame(float base) {
    Image image(8, 4);
    auto& counts = image.add_channel("counts");
    auto& std_dev = image.add_channel("counts_std");
    for (std::size_t i = 0; i < counts.size(); ++i) {
        counts[i] = base + static_cast<float>(i);
        std_dev[i] = 0.5f + static_cast<float>(i) * 0.01f;
    }
    return image;
}

SessionRecord polarizer_record(double angle, int repeat) {
    SessionRecord r;
    r.kind = RecordKind::Polarizer;
    r.file = session_frame_file(fmt::format("pol_{:05.1f}deg_r{}", angle, repeat));
    r.angle_deg_requested = angle;
    r.angle_deg_measured = angle + 0.001;
    r.repeat = repeat;
    r.frames = 16;
    r.dropped = 1;
    // A 2026 timestamp in ns does not fit a double exactly: the round trip must keep every digit.
    r.first_timestamp_ns = 1795359560123456789;
    r.last_timestamp_ns = 1795359560623456789;
    r.fpa_temperature_k = 305.25;
    return r;
}

TEST(Session, WriteThenReadRoundTripsManifestAndFrames) {
    test::TempDir tmp;
    const auto dir = tmp / "s";
    {
        auto writer = SessionWriter::create(dir, example_manifest());
        for (double a : {0.0, 45.0, 90.0, 135.0})
            writer.add_record(polarizer_record(a, 0), example_frame(static_cast<float>(a)));
        SessionRecord bb;
        bb.kind = RecordKind::Blackbody;
        bb.file = session_frame_file("bb_303.15K_r0");
        bb.blackbody_temperature_k = 303.15;
        bb.frames = 8;
        writer.add_record(bb, example_frame(1000.0f));
        writer.mark_complete();
    }
    const SessionManifest m = read_session(dir);
    EXPECT_EQ(m.records.size(), 5u);
    EXPECT_TRUE(m.complete);
    EXPECT_EQ(m.camera.planck_constants.at("B"), 1428.0);
    EXPECT_EQ(m.stage.counts_per_degree, 409600.0 / 3.0);
    EXPECT_EQ(m.metadata.at("site"), "roof");
    EXPECT_EQ(m.records[1], polarizer_record(45.0, 0));
    EXPECT_EQ(m.records[1].first_timestamp_ns, 1795359560123456789);
    EXPECT_FALSE(m.records[0].blackbody_temperature_k.has_value());
    EXPECT_EQ(*m.records[4].blackbody_temperature_k, 303.15);

    // The EXR carries the pixels and mirrors its record in the header.
    const Image frame = read_session_frame(dir, m, m.records[2]);
    EXPECT_EQ(frame.channel("counts"), example_frame(90.0f).channel("counts"));
    EXPECT_EQ(frame.channel("counts_std"), example_frame(90.0f).channel("counts_std"));
    EXPECT_EQ(record_from_attributes(frame.attributes(), m.records[2].file, "header"),
              m.records[2]);
    EXPECT_EQ(std::get<std::string>(frame.attributes().at("camera_uri")), "sim://panel");

    // The manifest is the documented schema, field for field.
    const json j = json::parse(read_file(dir / "session.json"));
    EXPECT_EQ(j.at("schema"), "tirpol.session");
    EXPECT_EQ(j.at("schema_version"), 6);
    EXPECT_TRUE(j.at("camera").at("microgrid_pattern_deg").is_null());
    EXPECT_TRUE(j.at("records")[0].at("blackbody_temperature_k").is_null());
    EXPECT_TRUE(j.at("ffc_events").is_array());
    EXPECT_EQ(j.at("records")[0].at("file"), "frames/pol_000.0deg_r0.exr");
}

StepTiming example_timing() {
    StepTiming t;
    t.move_start_ns = 1795359556000000001;
    t.move_end_ns = 1795359559000000002;
    t.settle_end_ns = 1795359559500000003;
    t.exposure_window_ns = 50'000'000;
    t.angle_deg_before_frames = 45.0004;
    t.angle_deg_after_frames = 45.0011;
    t.stale_frames_discarded = 31;
    return t;
}

TEST(Session, StepTimingRoundTripsThroughTheManifestAndTheFrameHeader) {
    test::TempDir tmp;
    SessionRecord r = polarizer_record(45.0, 0);
    r.timing = example_timing();
    {
        auto writer = SessionWriter::create(tmp / "s", example_manifest());
        writer.set_camera_frame_rate(29.7);
        writer.add_record(r, example_frame(1.0f));
    }
    const SessionManifest m = read_session(tmp / "s");
    EXPECT_EQ(m.schema_version, kSessionSchemaVersion);
    ASSERT_EQ(m.records.size(), 1u);
    EXPECT_EQ(m.records[0], r);  // every ns digit kept
    EXPECT_EQ(m.camera.frame_rate_hz.value_or(0.0), 29.7);
    const Image frame = read_session_frame(tmp / "s", m, m.records[0]);
    EXPECT_EQ(record_from_attributes(frame.attributes(), r.file, "header"), r);
    EXPECT_EQ(record_polarizer_angle_deg(m, m.records[0]), r.angle_deg_measured);
}

TEST(Session, FirstFrameBeforeTheSettleEndIsRefused) {
    test::TempDir tmp;
    SessionRecord r = polarizer_record(45.0, 0);
    r.timing = example_timing();
    r.timing->settle_end_ns = r.first_timestamp_ns + 1;
    auto writer = SessionWriter::create(tmp / "s", example_manifest());
    EXPECT_THAT([&] { writer.add_record(r, example_frame(1.0f)); },
                ::testing::ThrowsMessage<Error>(
                    HasSubstr("first_timestamp_ns: expected ≥ timing.settle_end_ns")));
}

TEST(Session, VersionOneSessionsStillReadAndUseTheRequestedAngle) {
    test::TempDir tmp;
    const auto dir = tmp / "v1";
    {
        auto writer = SessionWriter::create(dir, example_manifest());
        writer.add_record(polarizer_record(90.0, 0), example_frame(1.0f));
    }
    // What tirpol wrote before schema v2: same fields, version 1, no timing.
    json j = json::parse(read_file(dir / "session.json"));
    j["schema_version"] = 1;
    write_file_atomic(dir / "session.json", j.dump(2));
    const SessionManifest m = read_session(dir);
    EXPECT_EQ(m.schema_version, 1);
    EXPECT_FALSE(m.records[0].timing);
    // A v1 read-back preceded frames that may have been exposed mid-move: the request is the angle.
    EXPECT_EQ(record_polarizer_angle_deg(m, m.records[0]), 90.0);
    EXPECT_THAT([&] { SessionWriter::resume(dir); },
                ::testing::ThrowsMessage<Error>(HasSubstr("schema v1 session")));
}

TEST(Session, BlackbodyReadingsRoundTripThroughTheManifestAndTheFrameHeader) {
    // Schema v3: a controlled blackbody record keeps the controller's readings during its frames.
    test::TempDir tmp;
    SessionRecord r = polarizer_record(0.0, 0);
    r.kind = RecordKind::Blackbody;
    r.file = session_frame_file("s000_bb_303.15K");
    r.blackbody_temperature_k = 303.1487;
    r.timing = example_timing();
    r.blackbody_readings =
        BlackbodyReadings{303.15, 303.1487, 0.0042, 303.141, 303.157, 7, true, 41.25};
    SessionManifest manifest = example_manifest();
    manifest.blackbody_controller =
        SessionBlackbodyController{"fluke-4180:///dev/ttyUSB1", "FLUKE", "4180", "B12345", "1.10"};
    {
        auto writer = SessionWriter::create(tmp / "s", manifest);
        writer.add_record(r, example_frame(1.0f));
    }
    const SessionManifest m = read_session(tmp / "s");
    ASSERT_EQ(m.records.size(), 1u);
    EXPECT_EQ(m.records[0], r);
    EXPECT_EQ(m.blackbody_controller, manifest.blackbody_controller);
    const Image frame = read_session_frame(tmp / "s", m, m.records[0]);
    EXPECT_EQ(record_from_attributes(frame.attributes(), r.file, "header"), r);

    // A reading summary that contradicts itself names the field.
    json j = json::parse(read_file(tmp / "s" / "session.json"));
    j["records"][0]["blackbody_readings"]["min_k"] = 304.0;
    write_file_atomic(tmp / "s" / "session.json", j.dump(2));
    EXPECT_THAT([&] { read_session(tmp / "s"); },
                ::testing::ThrowsMessage<Error>(HasSubstr(
                    "records[0].blackbody_readings.mean_k: expected min_k ≤ mean_k ≤ max_k")));
}

TEST(Session, VersionTwoSessionsReadAndResume) {
    // v3 only adds optional fields: a v2 session (no controller) reads and can be continued.
    test::TempDir tmp;
    const auto dir = tmp / "v2";
    SessionRecord r = polarizer_record(90.0, 0);
    r.timing = example_timing();
    {
        auto writer = SessionWriter::create(dir, example_manifest());
        writer.add_record(r, example_frame(1.0f));
    }
    json j = json::parse(read_file(dir / "session.json"));
    j["schema_version"] = 2;
    j.erase("blackbody_controller");
    write_file_atomic(dir / "session.json", j.dump(2));
    const SessionManifest m = read_session(dir);
    EXPECT_EQ(m.schema_version, 2);
    EXPECT_FALSE(m.blackbody_controller);
    EXPECT_EQ(record_polarizer_angle_deg(m, m.records[0]), r.angle_deg_measured);
    auto writer = SessionWriter::resume(dir);
    writer.add_record(polarizer_record(45.0, 0), example_frame(2.0f));
    EXPECT_EQ(read_session(dir).records.size(), 2u);
}

TEST(Session, FfcEventsRoundTripAndVersionThreeSessionsWithoutThemRead) {
    // v4 adds ffc_events: every flat-field correction, scheduled or detected, kept exactly.
    test::TempDir tmp;
    const auto dir = tmp / "ffc";
    const FfcEvent scheduled{
        FfcEvent::Kind::Scheduled, 1795000000123456789, 0, 308.25, 1234, "every cycle"};
    const FfcEvent detected{
        FfcEvent::Kind::Detected,           1795000001123456789, 1, std::nullopt, std::nullopt,
        "frame mean stepped by 23.4 counts"};
    {
        auto writer = SessionWriter::create(dir, example_manifest());
        writer.add_ffc_event(scheduled);
        writer.add_ffc_event(detected);
    }
    SessionManifest m = read_session(dir);
    ASSERT_EQ(m.ffc_events.size(), 2u);
    EXPECT_EQ(m.ffc_events[0], scheduled);
    EXPECT_EQ(m.ffc_events[1], detected);
    json j = json::parse(read_file(dir / "session.json"));
    j["ffc_events"][0]["kind"] = "maybe";
    write_file_atomic(dir / "session.json", j.dump(2));
    EXPECT_THAT([&] { read_session(dir); },
                ::testing::ThrowsMessage<Error>(
                    HasSubstr("ffc_events[0].kind: expected \"scheduled\" or \"detected\"")));
    j["schema_version"] = 3;
    j.erase("ffc_events");
    write_file_atomic(dir / "session.json", j.dump(2));
    m = read_session(dir);
    EXPECT_EQ(m.schema_version, 3);
    EXPECT_TRUE(m.ffc_events.empty());
}

TEST(Session, MicrogridPatternRoundTripsIsCheckedAndVersionFourSessionsWithoutItRead) {
    // v5 records a microgrid camera's 2×2 analyzer layout (here the Sony IMX250MZR one).
    test::TempDir tmp;
    const auto dir = tmp / "dofp";
    SessionManifest manifest = example_manifest();
    manifest.camera.microgrid_pattern_deg = std::array<double, 4>{90.0, 45.0, 135.0, 0.0};
    { auto writer = SessionWriter::create(dir, manifest); }
    SessionManifest m = read_session(dir);
    ASSERT_TRUE(m.camera.microgrid_pattern_deg);
    EXPECT_EQ(*m.camera.microgrid_pattern_deg, (std::array<double, 4>{90.0, 45.0, 135.0, 0.0}));

    json j = json::parse(read_file(dir / "session.json"));
    j["camera"]["microgrid_pattern_deg"][2] = 180.0;
    write_file_atomic(dir / "session.json", j.dump(2));
    EXPECT_THAT([&] { read_session(dir); },
                ::testing::ThrowsMessage<Error>(HasSubstr(
                    "camera.microgrid_pattern_deg[2]: expected an angle in [0, 180) degrees")));
    j["camera"]["microgrid_pattern_deg"] = json::array({0.0, 45.0, 45.0, 135.0});
    write_file_atomic(dir / "session.json", j.dump(2));
    EXPECT_THAT([&] { read_session(dir); },
                ::testing::ThrowsMessage<Error>(
                    HasSubstr("camera.microgrid_pattern_deg[2]: 45 repeats entry 1")));
    j["camera"]["microgrid_pattern_deg"] = json::array({0.0, 45.0, 90.0});
    write_file_atomic(dir / "session.json", j.dump(2));
    EXPECT_THAT([&] { read_session(dir); },
                ::testing::ThrowsMessage<Error>(
                    HasSubstr("camera.microgrid_pattern_deg: expected null or an array of 4")));
    j["schema_version"] = 4;
    j["camera"].erase("microgrid_pattern_deg");
    write_file_atomic(dir / "session.json", j.dump(2));
    m = read_session(dir);
    EXPECT_EQ(m.schema_version, 4);
    EXPECT_FALSE(m.camera.microgrid_pattern_deg);
}

TEST(Session, FrameAuditRoundTripsAndItsColumnsMustMatchTheFrames) {
    test::TempDir tmp;
    const auto dir = tmp / "audit";
    SessionRecord r = polarizer_record(0.0, 0);
    r.frames = 2;
    FrameAudit a;
    a.frame_id = {41, 43};
    a.device_timestamp_ns = {1000000123, 1016666789};
    a.host_timestamp_ns = {1795000000123456789, 1795000000140123456};
    a.fpa_temperature_k = {308.15, std::nullopt};
    a.incomplete = 1;
    a.core_before = FrameAudit::CoreState{"manual", "high", 308.15, 1200, 1100};
    r.audit = a;
    {
        auto writer = SessionWriter::create(dir, example_manifest());
        writer.add_record(r, example_frame(1.0f));
    }
    const SessionManifest m = read_session(dir);
    ASSERT_EQ(m.records.size(), 1u);
    EXPECT_EQ(m.records[0], r);  // every digit of the 64-bit stamps kept, nulls kept
    json j = json::parse(read_file(dir / "session.json"));
    j["records"][0]["audit"]["frame_id"] = json::array({41});
    write_file_atomic(dir / "session.json", j.dump(2));
    EXPECT_THAT([&] { read_session(dir); },
                ::testing::ThrowsMessage<Error>(HasSubstr(
                    "records[0].audit.frame_id: expected 2 entries (the record's frames), got 1")));
}

TEST(Session, TelemetryAuditAndHomeChecksRoundTripAndVersionFiveSessionsWithoutThemRead) {
    // v6: per-frame core telemetry in the audit (a Lepton's frame counter and FFC state) and the
    // stage's lost-step checks.
    test::TempDir tmp;
    const auto dir = tmp / "v6";
    SessionRecord r = polarizer_record(0.0, 0);
    r.frames = 2;
    FrameAudit a;
    a.frame_id = {7, 8};
    a.device_timestamp_ns = {0, 0};
    a.host_timestamp_ns = {1795000000123456789, 1795000000140123456};
    a.fpa_temperature_k = {305.42, 305.43};
    a.device_frame_counter = {4294967295, std::nullopt};  // the core's 32-bit counter, whole
    a.ffc_state = {3, std::nullopt};
    r.audit = a;
    const HomeCheck good{1795000000200000000, true, 4, 4};
    const HomeCheck bad{1795000000300000000, false, 8, 4};
    {
        auto writer = SessionWriter::create(dir, example_manifest());
        writer.add_record(r, example_frame(1.0f));
        writer.add_home_check(good);
        writer.add_home_check(bad);
    }
    SessionManifest m = read_session(dir);
    ASSERT_EQ(m.records.size(), 1u);
    EXPECT_EQ(m.records[0], r);
    ASSERT_EQ(m.home_checks.size(), 2u);
    EXPECT_EQ(m.home_checks[0], good);
    EXPECT_EQ(m.home_checks[1], bad);

    json j = json::parse(read_file(dir / "session.json"));
    j["records"][0]["audit"]["ffc_state"][0] = 4;
    write_file_atomic(dir / "session.json", j.dump(2));
    EXPECT_THAT(
        [&] { read_session(dir); },
        ::testing::ThrowsMessage<Error>(HasSubstr(
            "records[0].audit.ffc_state[0]: expected an integer in [0, 3] or null, got number 4")));
    j["records"][0]["audit"]["ffc_state"][0] = 3;
    j["home_checks"][1]["passed"] = "no";
    write_file_atomic(dir / "session.json", j.dump(2));
    EXPECT_THAT([&] { read_session(dir); },
                ::testing::ThrowsMessage<Error>(HasSubstr("home_checks[1].passed")));
    // A v5 session has neither: it reads with both empty.
    j["schema_version"] = 5;
    j.erase("home_checks");
    j["records"][0]["audit"].erase("device_frame_counter");
    j["records"][0]["audit"].erase("ffc_state");
    write_file_atomic(dir / "session.json", j.dump(2));
    m = read_session(dir);
    EXPECT_EQ(m.schema_version, 5);
    EXPECT_TRUE(m.home_checks.empty());
    ASSERT_TRUE(m.records[0].audit);
    EXPECT_TRUE(m.records[0].audit->device_frame_counter.empty());
    EXPECT_TRUE(m.records[0].audit->ffc_state.empty());
}

TEST(Session, CreationThatFailsOnAFullDiskLeavesNothingBehind) {
    // A file-size limit makes write(2) fail as a full disk does (EFBIG instead of ENOSPC; SIGXFSZ
    // ignored).
    test::TempDir tmp;
    const auto dir = tmp / "s";
    rlimit old{};
    ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
    auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
    rlimit tiny = old;
    tiny.rlim_cur = 64;  // the manifest is larger
    ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &tiny), 0);
    std::string error;
    try {
        SessionWriter::create(dir, example_manifest());
    } catch (const Error& e) {
        error = e.what();
    }
    ::setrlimit(RLIMIT_FSIZE, &old);
    std::signal(SIGXFSZ, old_handler);
    EXPECT_THAT(error, HasSubstr("session.json"));
    // Nothing that a fresh start or --resume would trip over.
    EXPECT_FALSE(std::filesystem::exists(dir));
    for (const auto& e : std::filesystem::directory_iterator(tmp.path()))
        ADD_FAILURE() << "left behind: " << e.path();
    SessionWriter::create(dir, example_manifest());
    EXPECT_TRUE(read_session(dir).records.empty());
}

TEST(Session, CreateRemovesWhatACrashedCreationLeftAndResumeRemovesManifestTemporaries) {
    test::TempDir tmp;
    const auto dir = tmp / "s";
    // kill -9 during an earlier create: its hidden staging directory, whose lock nobody holds.
    test::write_text(tmp / ".s.creating-4242/frames/.keep", "");
    test::write_text(tmp / ".s.creating-4242/.lock", "");
    { SessionWriter::create(dir, example_manifest()); }
    EXPECT_FALSE(std::filesystem::exists(tmp / ".s.creating-4242"));
    // kill -9 during a manifest rewrite: write_file_atomic's temporary stays beside session.json.
    test::write_text(dir / ".session.json.tmp-4242-17.json", "{\"half\":");
    auto writer = SessionWriter::resume(dir);
    EXPECT_FALSE(std::filesystem::exists(dir / ".session.json.tmp-4242-17.json"));
}

TEST(Session, CreateRefusesANonEmptyDirectory) {
    test::TempDir tmp;
    test::write_text(tmp / "d/notes.txt", "x");
    EXPECT_THAT([&] { SessionWriter::create(tmp / "d", example_manifest()); },
                ::testing::ThrowsMessage<Error>(HasSubstr("not empty")));
    SessionWriter::create(tmp / "empty", example_manifest());  // a fresh or empty directory is fine
    EXPECT_TRUE(std::filesystem::exists(tmp / "empty/session.json"));
}

TEST(Session, NeverOverwritesAFrame) {
    test::TempDir tmp;
    auto writer = SessionWriter::create(tmp / "s", example_manifest());
    writer.add_record(polarizer_record(0, 0), example_frame(1.0f));
    EXPECT_THAT([&] { writer.add_record(polarizer_record(0, 0), example_frame(2.0f)); },
                ::testing::ThrowsMessage<Error>(HasSubstr("already recorded")));
    // A stray file with the name of a new record is not replaced either.
    test::write_text(tmp / "s/frames/pol_045.0deg_r0.exr", "not mine");
    EXPECT_THAT([&] { writer.add_record(polarizer_record(45, 0), example_frame(2.0f)); },
                ::testing::ThrowsMessage<Error>(HasSubstr("already exists")));
    EXPECT_EQ(read_file(tmp / "s/frames/pol_045.0deg_r0.exr"), "not mine");
    EXPECT_EQ(read_exr(tmp / "s/frames/pol_000.0deg_r0.exr").channel("counts")[0], 1.0f);
    EXPECT_EQ(read_session(tmp / "s").records.size(), 1u);
}

TEST(Session, ResumeKnowsWhatIsDoneAndAdoptsAFrameTheManifestMissed) {
    test::TempDir tmp;
    const auto dir = tmp / "s";
    {
        auto writer = SessionWriter::create(dir, example_manifest());
        writer.add_record(polarizer_record(0, 0), example_frame(0.0f));
    }
    // Simulate a crash after the second frame reached the disk but before the manifest was
    // rewritten, plus a temporary file of a third write that was cut off.
    Image orphan = example_frame(45.0f);
    record_to_attributes(polarizer_record(45, 0), orphan.attributes());
    write_exr(dir / "frames/pol_045.0deg_r0.exr", orphan);
    test::write_text(dir / "frames/.pol_090.0deg_r0.exr.tmp-123-456.exr", "half");
    ASSERT_EQ(read_session(dir).records.size(), 1u);

    auto writer = SessionWriter::resume(dir);
    EXPECT_TRUE(writer.has_record("frames/pol_000.0deg_r0.exr"));
    EXPECT_TRUE(writer.has_record("frames/pol_045.0deg_r0.exr"));
    EXPECT_FALSE(writer.has_record("frames/pol_090.0deg_r0.exr"));
    EXPECT_EQ(writer.adopted_files(), std::vector<std::string>{"frames/pol_045.0deg_r0.exr"});
    EXPECT_FALSE(std::filesystem::exists(dir / "frames/.pol_090.0deg_r0.exr.tmp-123-456.exr"));
    writer.add_record(polarizer_record(90, 0), example_frame(90.0f));
    writer.mark_complete();
    const auto m = read_session(dir);
    ASSERT_EQ(m.records.size(), 3u);
    EXPECT_EQ(m.records[1], polarizer_record(45, 0));
    EXPECT_TRUE(m.complete);
    EXPECT_THAT([&] { writer.add_record(polarizer_record(135, 0), example_frame(1.0f)); },
                ::testing::ThrowsMessage<Error>(HasSubstr("complete")));
}

TEST(Session, OnlyOneWriterAtATime) {
    test::TempDir tmp;
    auto first = SessionWriter::create(tmp / "s", example_manifest());
    EXPECT_THAT([&] { SessionWriter::resume(tmp / "s"); },
                ::testing::ThrowsMessage<Error>(HasSubstr("another process")));
}

class DamagedSession : public ::testing::Test {
protected:
    void SetUp() override {
        auto writer = SessionWriter::create(dir(), example_manifest());
        writer.add_record(polarizer_record(0, 0), example_frame(0.0f));
        writer.add_record(polarizer_record(45, 0), example_frame(1.0f));
        m_original = json::parse(read_file(dir() / "session.json"));
    }
    std::filesystem::path dir() const { return m_tmp / "s"; }
    const json& manifest() const { return m_original; }
    void write(const json& j) const { write_file_atomic(dir() / "session.json", j.dump()); }
    std::string error_of_read() const {
        try {
            read_session(dir());
        } catch (const Error& e) {
            return e.what();
        }
        return "";
    }
    test::TempDir m_tmp;
    json m_original;
};

TEST_F(DamagedSession, TruncatedManifestNamesTheFile) {
    const std::string text = read_file(dir() / "session.json");
    write_file_atomic(dir() / "session.json", text.substr(0, text.size() / 2));
    EXPECT_THAT(error_of_read(), HasSubstr("session.json: not valid JSON"));
}

TEST_F(DamagedSession, WrongSchemaVersionIsRefused) {
    json j = manifest();
    j["schema_version"] = 7;
    write(j);
    EXPECT_THAT(error_of_read(), HasSubstr("schema_version: expected 1 to 6, got 7"));
    j["schema"] = "something.else";
    write(j);
    EXPECT_THAT(error_of_read(), HasSubstr("schema: expected \"tirpol.session\""));
}

TEST_F(DamagedSession, BadRecordFieldIsNamed) {
    json j = manifest();
    j["records"][1].erase("frames");
    write(j);
    EXPECT_THAT(error_of_read(), HasSubstr("records[1].frames: missing field"));
    j = manifest();
    j["records"][0]["frames"] = "sixteen";
    write(j);
    EXPECT_THAT(error_of_read(), HasSubstr("records[0].frames: expected an integer, got string"));
    j = manifest();
    j["records"][0]["kind"] = "blackbody";  // a blackbody record needs its temperature
    write(j);
    EXPECT_THAT(error_of_read(), HasSubstr("records[0].blackbody_temperature_k"));
    j = manifest();
    j["records"][1]["file"] = "../elsewhere.exr";
    write(j);
    EXPECT_THAT(error_of_read(), HasSubstr("records[1].file: expected \"frames/<name>.exr\""));
    j = manifest();
    j["records"][1]["file"] = j["records"][0]["file"];
    write(j);
    EXPECT_THAT(error_of_read(), HasSubstr("listed twice"));
    j = manifest();
    j["camera"]["width"] = -3;
    write(j);
    EXPECT_THAT(error_of_read(), HasSubstr("camera.width: expected an integer ≥ 1, got -3"));
}

TEST_F(DamagedSession, MissingFrameFileIsNamed) {
    std::filesystem::remove(dir() / "frames/pol_045.0deg_r0.exr");
    EXPECT_THAT(error_of_read(), HasSubstr("records[1].file: frame file"));
    EXPECT_THAT(error_of_read(), HasSubstr("pol_045.0deg_r0.exr is missing"));
}

TEST_F(DamagedSession, TruncatedFrameIsReportedWhenRead) {
    const auto m = read_session(dir());
    const auto path = dir() / m.records[0].file;
    const std::string bytes = read_file(path);
    write_file_atomic(path, bytes.substr(0, bytes.size() / 2));
    EXPECT_THAT([&] { read_session_frame(dir(), m, m.records[0]); },
                ::testing::ThrowsMessage<Error>(HasSubstr("pol_000.0deg_r0.exr")));
}

TEST(Session, FrameNamesAreRestrictedToSafeCharacters) {
    EXPECT_EQ(session_frame_file("pol_045deg_r1"), "frames/pol_045deg_r1.exr");
    EXPECT_THROW(session_frame_file("../x"), Error);
    EXPECT_THROW(session_frame_file("a/b"), Error);
    EXPECT_THROW(session_frame_file(""), Error);
}

}  // namespace
}  // namespace tirpol
