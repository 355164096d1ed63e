// summarize_session: what `tirpol info SESSION` shows a reviewer, counted from a manifest whose
// contents are known.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tirpol/core/path_info.h"

namespace tirpol {
namespace {

SessionRecord record(RecordKind kind, std::int64_t frames, std::int64_t dropped) {
    SessionRecord r;
    r.kind = kind;
    r.frames = frames;
    r.dropped = dropped;
    return r;
}

TEST(SessionSummary, CountsRecordsAuditTelemetryFfcsAndHomeChecks) {
    SessionManifest m;
    m.schema_version = 6;
    m.complete = true;
    m.records.push_back(record(RecordKind::Polarizer, 2, 1));
    m.records.push_back(record(RecordKind::Polarizer, 2, 0));
    m.records.push_back(record(RecordKind::Blackbody, 3, 0));  // adopted on resume: no audit
    FrameAudit a;
    a.device_timestamp_ns = {0, 12};
    a.fpa_temperature_k = {305.5, std::nullopt};
    a.device_frame_counter = {10, 11};
    a.ffc_state = {3, 2};  // the second frame was kept while the shutter was closed
    a.incomplete = 2;
    m.records[0].audit = a;
    FrameAudit b;
    b.device_timestamp_ns = {5, 6};
    b.fpa_temperature_k = {304.25, 306.0};
    b.incomplete = 1;
    m.records[1].audit = b;
    m.ffc_events = {FfcEvent{FfcEvent::Kind::Scheduled, 1, 0, {}, {}, "every cycle"},
                    FfcEvent{FfcEvent::Kind::Detected, 2, 0, {}, {}, "closure"},
                    FfcEvent{FfcEvent::Kind::Scheduled, 3, 0, {}, {}, "retake"}};
    m.home_checks = {HomeCheck{100, true, 4, 4}, HomeCheck{200, false, 8, 4}};

    const SessionSummary s = summarize_session(m);
    EXPECT_EQ(s.records, 3u);
    EXPECT_EQ(s.polarizer_records, 2u);
    EXPECT_EQ(s.reference_records, 1u);
    EXPECT_EQ(s.frames, 7);
    EXPECT_EQ(s.dropped, 1);
    EXPECT_EQ(s.incomplete, 3);
    EXPECT_EQ(s.audited_records, 2u);
    EXPECT_EQ(s.frames_with_device_clock, 3);  // a 0 stamp means the camera has no clock
    EXPECT_EQ(s.frames_with_core_telemetry, 2);
    EXPECT_EQ(s.frames_during_ffc, 1);
    EXPECT_EQ(s.fpa_min_k, 304.25);
    EXPECT_EQ(s.fpa_max_k, 306.0);
    EXPECT_EQ(s.ffc_scheduled, 2);
    EXPECT_EQ(s.ffc_detected, 1);
    EXPECT_EQ(s.home_checks_passed, 1);
    EXPECT_EQ(s.home_checks_failed, 1);
    const auto j = session_summary_to_json(s);
    EXPECT_EQ(j.at("home_checks")[1].at("passed"), false);
    EXPECT_EQ(j.at("home_checks")[1].at("steps_since_last_good"), 4);
    EXPECT_TRUE(summarize_session(SessionManifest{}).fpa_min_k == std::nullopt);
}

// The text `tirpol info SESSION` prints: every count in its sentence, each home check with its
// 1-based step and UTC time (1 700 000 000 s = 2023-11-14T22:13:20Z).
TEST(SessionSummary, TextStatesCountsAndEachHomeCheckInUtc) {
    SessionManifest m;
    m.schema_version = 6;
    m.complete = false;
    m.records.push_back(record(RecordKind::Polarizer, 4, 2));
    m.home_checks = {HomeCheck{1'700'000'000'000'000'000, false, 3, 12}};
    const std::string text = session_summary_text(summarize_session(m), "run1");
    using ::testing::HasSubstr;
    EXPECT_THAT(text, HasSubstr("run1: capture session, schema v6, incomplete, created \n"));
    EXPECT_THAT(text, HasSubstr("  records: 1 (1 polarizer, 0 reference), 4 frames averaged\n"));
    EXPECT_THAT(text, HasSubstr("  camera losses: 2 dropped, 0 incomplete\n"));
    EXPECT_THAT(text, HasSubstr("0 passed, 1 failed\n"));
    EXPECT_THAT(text, HasSubstr("    before step 4: FAILED (lost steps), 12 steps since the last "
                                "good check, at 2023-11-14T22:13:20Z\n"));
    EXPECT_THAT(text, ::testing::Not(HasSubstr("FPA temperature")));
}

}  // namespace
}  // namespace tirpol
