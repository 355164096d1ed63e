#include <fmt/printf.h>

#include <algorithm>
#include <ctime>

#include "tirpol/core/path_info.h"

namespace tirpol {

SessionSummary summarize_session(const SessionManifest& m) {
    SessionSummary s;
    s.schema_version = m.schema_version;
    s.complete = m.complete;
    s.created_utc = m.created_utc;
    s.camera_uri = m.camera.uri;
    s.stage_uri = m.stage.uri;
    s.records = m.records.size();
    for (const auto& r : m.records) {
        (r.kind == RecordKind::Polarizer ? s.polarizer_records : s.reference_records)++;
        s.frames += r.frames;
        s.dropped += r.dropped;
        if (!r.audit) continue;
        const FrameAudit& a = *r.audit;
        ++s.audited_records;
        s.incomplete += a.incomplete;
        for (std::int64_t t : a.device_timestamp_ns) s.frames_with_device_clock += t != 0;
        for (const auto& c : a.device_frame_counter) s.frames_with_core_telemetry += c.has_value();
        for (const auto& st : a.ffc_state) s.frames_during_ffc += st && (*st == 1 || *st == 2);
        for (const auto& t : a.fpa_temperature_k) {
            if (!t) continue;
            s.fpa_min_k = s.fpa_min_k ? std::min(*s.fpa_min_k, *t) : *t;
            s.fpa_max_k = s.fpa_max_k ? std::max(*s.fpa_max_k, *t) : *t;
        }
    }
    for (const auto& e : m.ffc_events)
        (e.kind == FfcEvent::Kind::Scheduled ? s.ffc_scheduled : s.ffc_detected)++;
    s.home_checks = m.home_checks;
    for (const auto& c : m.home_checks) (c.passed ? s.home_checks_passed : s.home_checks_failed)++;
    return s;
}

nlohmann::json session_summary_to_json(const SessionSummary& s) {
    using nlohmann::json;
    auto optional = [](const std::optional<double>& v) { return v ? json(*v) : json(nullptr); };
    json checks = json::array();
    for (const auto& c : s.home_checks)
        checks.push_back({{"host_timestamp_ns", c.host_timestamp_ns},
                          {"passed", c.passed},
                          {"before_step", c.before_step},
                          {"steps_since_last_good", c.steps_since_last_good}});
    return json{{"schema_version", s.schema_version},
                {"complete", s.complete},
                {"created_utc", s.created_utc},
                {"camera_uri", s.camera_uri},
                {"stage_uri", s.stage_uri},
                {"records", s.records},
                {"polarizer_records", s.polarizer_records},
                {"reference_records", s.reference_records},
                {"frames", s.frames},
                {"dropped", s.dropped},
                {"incomplete", s.incomplete},
                {"audited_records", s.audited_records},
                {"frames_with_device_clock", s.frames_with_device_clock},
                {"frames_with_core_telemetry", s.frames_with_core_telemetry},
                {"frames_during_ffc", s.frames_during_ffc},
                {"fpa_min_k", optional(s.fpa_min_k)},
                {"fpa_max_k", optional(s.fpa_max_k)},
                {"ffc_scheduled", s.ffc_scheduled},
                {"ffc_detected", s.ffc_detected},
                {"home_checks_passed", s.home_checks_passed},
                {"home_checks_failed", s.home_checks_failed},
                {"home_checks", checks}};
}

namespace {
std::string utc_text(std::int64_t host_ns) {
    const std::time_t seconds = static_cast<std::time_t>(host_ns / 1'000'000'000);
    std::tm utc{};
    gmtime_r(&seconds, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return text;
}
}  // namespace

std::string session_summary_text(const SessionSummary& s, const std::string& dir) {
    std::string text =
        fmt::sprintf("%s: capture session, schema v%d, %s, created %s\n", dir, s.schema_version,
                     s.complete ? "complete" : "incomplete", s.created_utc);
    text += fmt::sprintf("  camera %s, stage %s\n", s.camera_uri, s.stage_uri);
    text += fmt::sprintf("  records: %zu (%zu polarizer, %zu reference), %lld frames averaged\n",
                         s.records, s.polarizer_records, s.reference_records,
                         static_cast<long long>(s.frames));
    text += fmt::sprintf("  camera losses: %lld dropped, %lld incomplete\n",
                         static_cast<long long>(s.dropped), static_cast<long long>(s.incomplete));
    text += fmt::sprintf(
        "  audit: %zu of %zu records per frame; %lld frames with a device clock, %lld with the "
        "core's telemetry, %lld kept during an FFC\n",
        s.audited_records, s.records, static_cast<long long>(s.frames_with_device_clock),
        static_cast<long long>(s.frames_with_core_telemetry),
        static_cast<long long>(s.frames_during_ffc));
    if (s.fpa_min_k)
        text += fmt::sprintf("  FPA temperature: %.2f to %.2f K\n", *s.fpa_min_k, *s.fpa_max_k);
    text += fmt::sprintf(
        "  flat-field corrections: %d scheduled between cycles, %d detected inside a cycle\n",
        s.ffc_scheduled, s.ffc_detected);
    text += fmt::sprintf("  lost-step checks at the home sensor: %d passed, %d failed\n",
                         s.home_checks_passed, s.home_checks_failed);
    for (const auto& c : s.home_checks)
        text += fmt::sprintf(
            "    before step %d: %s, %lld steps since the last good check, at %s\n",
            c.before_step + 1, c.passed ? "passed" : "FAILED (lost steps)",
            static_cast<long long>(c.steps_since_last_good), utc_text(c.host_timestamp_ns));
    return text;
}

}  // namespace tirpol
