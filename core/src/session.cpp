#include "tirpol/core/session.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <ctime>
#include <limits>
#include <set>

#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/output_guard.h"
#include "tirpol/core/utf8.h"

namespace tirpol {

using nlohmann::json;

const char* to_string(RecordKind kind) {
    switch (kind) {
        case RecordKind::Polarizer:
            return "polarizer";
        case RecordKind::Blackbody:
            return "blackbody";
        case RecordKind::Shutter:
            return "shutter";
    }
    return "?";
}

std::optional<RecordKind> record_kind_from_string(const std::string& text) {
    if (text == "polarizer") return RecordKind::Polarizer;
    if (text == "blackbody") return RecordKind::Blackbody;
    if (text == "shutter") return RecordKind::Shutter;
    return std::nullopt;
}

double record_polarizer_angle_deg(const SessionManifest& manifest, const SessionRecord& record) {
    return manifest.schema_version >= 2 ? record.angle_deg_measured : record.angle_deg_requested;
}

std::string session_frame_file(const std::string& stem) {
    if (stem.empty() || stem.front() == '.')
        fail("session frame name '{}': expected a non-empty name not starting with '.'", stem);
    for (char c : stem) {
        const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') ||
                        (c >= '0' && c <= '9') || c == '.' || c == '_' || c == '+' || c == '-';
        if (!ok)
            fail("session frame name '{}': character '{}' not allowed (use A-Z a-z 0-9 . _ + -)",
                 stem, c);
    }
    return "frames/" + stem + ".exr";
}

// ---- JSON ⇄ manifest ----------------------------------------------------------------------------

namespace {

json optional_number(const std::optional<double>& v) { return v ? json(*v) : json(nullptr); }

/// Typed access to one JSON object with errors "<source>: <path>.<key>: expected ..., got ...".
class Fields {
public:
    Fields(const json& j, std::string source, std::string path)
        : m_j(j), m_source(std::move(source)), m_path(std::move(path)) {
        if (!m_j.is_object()) fail_here(m_path, "expected an object, got " + describe(m_j));
    }
    const json& at(const std::string& key) const {
        auto it = m_j.find(key);
        if (it == m_j.end()) fail_here(field(key), "missing field");
        return *it;
    }
    std::string string(const std::string& key) const {
        const json& v = at(key);
        if (!v.is_string()) fail_here(field(key), "expected a string, got " + describe(v));
        return v.get<std::string>();
    }
    double number(const std::string& key) const {
        const json& v = at(key);
        if (!v.is_number()) fail_here(field(key), "expected a number, got " + describe(v));
        const double d = v.get<double>();
        if (!std::isfinite(d)) fail_here(field(key), "expected a finite number");
        return d;
    }
    std::optional<double> optional_number(const std::string& key) const {
        if (at(key).is_null()) return std::nullopt;
        return number(key);
    }
    std::int64_t integer(const std::string& key, std::int64_t min,
                         std::int64_t max = std::numeric_limits<std::int64_t>::max()) const {
        const json& v = at(key);
        if (!v.is_number_integer())
            fail_here(field(key), "expected an integer, got " + describe(v));
        if (v.is_number_unsigned() && v.get<std::uint64_t>() > static_cast<std::uint64_t>(max))
            fail_here(field(key), fmt::format("expected an integer in [{}, {}], got {}", min, max,
                                              json_text(v)));
        const auto i = v.get<std::int64_t>();
        if (i < min) fail_here(field(key), fmt::format("expected an integer ≥ {}, got {}", min, i));
        if (i > max)
            fail_here(field(key),
                      fmt::format("expected an integer in [{}, {}], got {}", min, max, i));
        return i;
    }
    bool boolean(const std::string& key) const {
        const json& v = at(key);
        if (!v.is_boolean()) fail_here(field(key), "expected true or false, got " + describe(v));
        return v.get<bool>();
    }
    Fields object(const std::string& key) const { return Fields(at(key), m_source, field(key)); }
    std::string field(const std::string& key) const {
        return m_path.empty() ? key : m_path + "." + key;
    }
    [[noreturn]] void fail_here(const std::string& path, const std::string& message) const {
        fail("{}: {}: {}", m_source, path.empty() ? "(top level)" : path, message);
    }
    const json& raw() const { return m_j; }

    static std::string describe(const json& v) {
        std::string text = json_text(v);
        if (text.size() > 40) text = text.substr(0, 37) + "...";
        return std::string(v.type_name()) + " " + text;
    }

private:
    const json& m_j;
    std::string m_source;
    std::string m_path;
};

json timing_to_json(const StepTiming& t) {
    return json{{"move_start_ns", t.move_start_ns},
                {"move_end_ns", t.move_end_ns},
                {"settle_end_ns", t.settle_end_ns},
                {"exposure_window_ns", t.exposure_window_ns},
                {"angle_deg_before_frames", t.angle_deg_before_frames},
                {"angle_deg_after_frames", t.angle_deg_after_frames},
                {"stale_frames_discarded", t.stale_frames_discarded}};
}

StepTiming timing_from_json(const Fields& f) {
    StepTiming t;
    t.move_start_ns = f.integer("move_start_ns", 0);
    t.move_end_ns = f.integer("move_end_ns", t.move_start_ns);
    t.settle_end_ns = f.integer("settle_end_ns", t.move_end_ns);
    t.exposure_window_ns = f.integer("exposure_window_ns", 0);
    t.angle_deg_before_frames = f.number("angle_deg_before_frames");
    t.angle_deg_after_frames = f.number("angle_deg_after_frames");
    t.stale_frames_discarded = f.integer("stale_frames_discarded", 0);
    for (const char* key : {"angle_deg_before_frames", "angle_deg_after_frames"}) {
        const double a = f.number(key);
        if (!(a > -360.0 && a < 720.0))
            f.fail_here(f.field(key), fmt::format("expected an angle in degrees, got {}", a));
    }
    return t;
}

json readings_to_json(const BlackbodyReadings& b) {
    return json{{"set_point_k", b.set_point_k},
                {"mean_k", b.mean_k},
                {"std_k", b.std_k},
                {"min_k", b.min_k},
                {"max_k", b.max_k},
                {"readings", b.readings},
                {"stable", b.stable},
                {"wait_s", b.wait_s}};
}

BlackbodyReadings readings_from_json(const Fields& f) {
    BlackbodyReadings b;
    b.set_point_k = f.number("set_point_k");
    b.mean_k = f.number("mean_k");
    b.std_k = f.number("std_k");
    b.min_k = f.number("min_k");
    b.max_k = f.number("max_k");
    b.readings = f.integer("readings", 1);
    b.stable = f.boolean("stable");
    b.wait_s = f.number("wait_s");
    for (const char* key : {"set_point_k", "mean_k", "min_k", "max_k"}) {
        const double t = f.number(key);
        if (!(t >= limits::kMinTemperatureK && t <= limits::kMaxTemperatureK))
            f.fail_here(f.field(key),
                        fmt::format("expected a temperature in [{}, {}] K, got {}",
                                    limits::kMinTemperatureK, limits::kMaxTemperatureK, t));
    }
    if (!(b.min_k <= b.mean_k && b.mean_k <= b.max_k))
        f.fail_here(f.field("mean_k"),
                    fmt::format("expected min_k ≤ mean_k ≤ max_k, got {} ≤ {} ≤ {}", b.min_k,
                                b.mean_k, b.max_k));
    if (!(b.std_k >= 0.0))
        f.fail_here(f.field("std_k"), fmt::format("expected ≥ 0, got {}", b.std_k));
    if (!(b.wait_s >= 0.0))
        f.fail_here(f.field("wait_s"), fmt::format("expected ≥ 0 s, got {}", b.wait_s));
    return b;
}

json core_state_to_json(const FrameAudit::CoreState& c) {
    return json{{"ffc_mode", c.ffc_mode},
                {"gain_mode", c.gain_mode},
                {"fpa_temperature_k", c.fpa_temperature_k},
                {"device_frame_count", c.device_frame_count},
                {"last_ffc_frame_count", c.last_ffc_frame_count}};
}

json audit_to_json(const FrameAudit& a) {
    json fpa = json::array();
    for (const auto& t : a.fpa_temperature_k) fpa.push_back(optional_number(t));
    json j{{"frame_id", a.frame_id},
           {"device_timestamp_ns", a.device_timestamp_ns},
           {"host_timestamp_ns", a.host_timestamp_ns},
           {"fpa_temperature_k", fpa},
           {"incomplete", a.incomplete},
           {"core_before", a.core_before ? core_state_to_json(*a.core_before) : json(nullptr)},
           {"core_after", a.core_after ? core_state_to_json(*a.core_after) : json(nullptr)}};
    if (!a.device_frame_counter.empty() || !a.ffc_state.empty()) {
        json counters = json::array(), states = json::array();
        for (const auto& c : a.device_frame_counter)
            counters.push_back(c ? json(*c) : json(nullptr));
        for (const auto& st : a.ffc_state) states.push_back(st ? json(*st) : json(nullptr));
        j["device_frame_counter"] = counters;
        j["ffc_state"] = states;
    }
    return j;
}

std::optional<FrameAudit::CoreState> core_state_from_json(const Fields& f, const std::string& key) {
    if (f.at(key).is_null()) return std::nullopt;
    const Fields c = f.object(key);
    return FrameAudit::CoreState{c.string("ffc_mode"), c.string("gain_mode"),
                                 c.number("fpa_temperature_k"), c.integer("device_frame_count", 0),
                                 c.integer("last_ffc_frame_count", 0)};
}

FrameAudit audit_from_json(const Fields& f, std::int64_t frames) {
    FrameAudit a;
    auto column = [&](const char* key) -> const json& {
        const json& v = f.at(key);
        if (!v.is_array())
            f.fail_here(f.field(key), "expected an array, got " + Fields::describe(v));
        if (static_cast<std::int64_t>(v.size()) != frames)
            f.fail_here(
                f.field(key),
                fmt::format("expected {} entries (the record's frames), got {}", frames, v.size()));
        return v;
    };
    auto integers = [&](const char* key, std::vector<std::int64_t>& out) {
        const json& v = column(key);
        for (std::size_t i = 0; i < v.size(); ++i) {
            if (!v[i].is_number_integer())
                f.fail_here(fmt::format("{}[{}]", f.field(key), i),
                            "expected an integer, got " + Fields::describe(v[i]));
            out.push_back(v[i].get<std::int64_t>());
        }
    };
    integers("frame_id", a.frame_id);
    integers("device_timestamp_ns", a.device_timestamp_ns);
    integers("host_timestamp_ns", a.host_timestamp_ns);
    const json& fpa = column("fpa_temperature_k");
    for (std::size_t i = 0; i < fpa.size(); ++i) {
        if (fpa[i].is_null()) {
            a.fpa_temperature_k.emplace_back();
        } else if (fpa[i].is_number() && std::isfinite(fpa[i].get<double>())) {
            a.fpa_temperature_k.emplace_back(fpa[i].get<double>());
        } else {
            f.fail_here(fmt::format("{}[{}]", f.field("fpa_temperature_k"), i),
                        "expected a number or null, got " + Fields::describe(fpa[i]));
        }
    }
    // v6: present only when the frames carried the core's telemetry.
    auto optional_integers = [&](const char* key, std::int64_t lo, std::int64_t hi, auto& out) {
        if (!f.raw().contains(key)) return;
        const json& v = column(key);
        for (std::size_t i = 0; i < v.size(); ++i) {
            if (v[i].is_null()) {
                out.emplace_back();
            } else if (v[i].is_number_integer() && v[i].get<std::int64_t>() >= lo &&
                       v[i].get<std::int64_t>() <= hi) {
                out.emplace_back(
                    static_cast<typename std::decay_t<decltype(out)>::value_type::value_type>(
                        v[i].get<std::int64_t>()));
            } else {
                f.fail_here(fmt::format("{}[{}]", f.field(key), i),
                            fmt::format("expected an integer in [{}, {}] or null, got {}", lo, hi,
                                        Fields::describe(v[i])));
            }
        }
    };
    optional_integers("device_frame_counter", 0, 0xFFFFFFFFll, a.device_frame_counter);
    optional_integers("ffc_state", 0, 3, a.ffc_state);
    a.incomplete = f.integer("incomplete", 0);
    a.core_before = core_state_from_json(f, "core_before");
    a.core_after = core_state_from_json(f, "core_after");
    return a;
}

json record_to_json(const SessionRecord& r) {
    json j{{"kind", to_string(r.kind)},
           {"file", r.file},
           {"angle_deg_requested", r.angle_deg_requested},
           {"angle_deg_measured", r.angle_deg_measured},
           {"repeat", r.repeat},
           {"blackbody_temperature_k", optional_number(r.blackbody_temperature_k)},
           {"frames", r.frames},
           {"dropped", r.dropped},
           {"first_timestamp_ns", r.first_timestamp_ns},
           {"last_timestamp_ns", r.last_timestamp_ns},
           {"fpa_temperature_k", optional_number(r.fpa_temperature_k)}};
    if (r.timing) j["timing"] = timing_to_json(*r.timing);
    if (r.blackbody_readings) j["blackbody_readings"] = readings_to_json(*r.blackbody_readings);
    if (r.audit) j["audit"] = audit_to_json(*r.audit);
    return j;
}

void check_frame_path(const Fields& f, const std::string& key, const std::string& file) {
    const std::string prefix = "frames/", suffix = ".exr";
    const bool shaped = file.size() > prefix.size() + suffix.size() &&
                        file.compare(0, prefix.size(), prefix) == 0 &&
                        file.compare(file.size() - suffix.size(), suffix.size(), suffix) == 0;
    if (!shaped) f.fail_here(f.field(key), "expected \"frames/<name>.exr\", got \"" + file + "\"");
    const std::string stem =
        file.substr(prefix.size(), file.size() - prefix.size() - suffix.size());
    try {
        session_frame_file(stem);
    } catch (const Error& e) {
        f.fail_here(f.field(key), e.what());
    }
}

// Record semantics shared by the manifest and EXR-header readers.
void check_record(const Fields& f, const SessionRecord& r) {
    if (!(r.angle_deg_requested >= 0.0 && r.angle_deg_requested < 360.0))
        f.fail_here(
            f.field("angle_deg_requested"),
            fmt::format("expected an angle in [0, 360) degrees, got {}", r.angle_deg_requested));
    if (!(r.angle_deg_measured > -360.0 && r.angle_deg_measured < 720.0))
        f.fail_here(f.field("angle_deg_measured"),
                    fmt::format("expected an angle in degrees, got {}", r.angle_deg_measured));
    if (r.kind == RecordKind::Polarizer && r.blackbody_temperature_k)
        f.fail_here(f.field("blackbody_temperature_k"), "expected null for a polarizer record");
    if (r.kind == RecordKind::Blackbody && !r.blackbody_temperature_k)
        f.fail_here(f.field("blackbody_temperature_k"),
                    "expected a temperature in kelvin for a blackbody record, got null");
    const auto in_range = [](double t_k) {
        return t_k >= limits::kMinTemperatureK && t_k <= limits::kMaxTemperatureK;
    };
    if (r.blackbody_temperature_k && !in_range(*r.blackbody_temperature_k))
        f.fail_here(
            f.field("blackbody_temperature_k"),
            fmt::format("expected a temperature in [{}, {}] K, got {}", limits::kMinTemperatureK,
                        limits::kMaxTemperatureK, *r.blackbody_temperature_k));
    if (r.fpa_temperature_k && !in_range(*r.fpa_temperature_k))
        f.fail_here(
            f.field("fpa_temperature_k"),
            fmt::format("expected a temperature in [{}, {}] K or null, got {}",
                        limits::kMinTemperatureK, limits::kMaxTemperatureK, *r.fpa_temperature_k));
    if (r.last_timestamp_ns < r.first_timestamp_ns)
        f.fail_here(f.field("last_timestamp_ns"),
                    fmt::format("expected ≥ first_timestamp_ns ({}), got {}", r.first_timestamp_ns,
                                r.last_timestamp_ns));
}

SessionRecord record_from_json(const Fields& f) {
    SessionRecord r;
    const std::string kind = f.string("kind");
    const auto parsed = record_kind_from_string(kind);
    if (!parsed)
        f.fail_here(f.field("kind"),
                    "expected \"polarizer\", \"blackbody\" or \"shutter\", got \"" + kind + "\"");
    r.kind = *parsed;
    r.file = f.string("file");
    check_frame_path(f, "file", r.file);
    r.angle_deg_requested = f.number("angle_deg_requested");
    r.angle_deg_measured = f.number("angle_deg_measured");
    r.repeat = static_cast<int>(f.integer("repeat", 0));
    r.blackbody_temperature_k = f.optional_number("blackbody_temperature_k");
    r.frames = f.integer("frames", 1);
    r.dropped = f.integer("dropped", 0);
    r.first_timestamp_ns = f.integer("first_timestamp_ns", 0);
    r.last_timestamp_ns = f.integer("last_timestamp_ns", 0);
    r.fpa_temperature_k = f.optional_number("fpa_temperature_k");
    if (f.raw().contains("timing") && !f.raw().at("timing").is_null()) {
        r.timing = timing_from_json(f.object("timing"));
        if (r.first_timestamp_ns < r.timing->settle_end_ns)
            f.fail_here(f.field("first_timestamp_ns"),
                        fmt::format("expected ≥ timing.settle_end_ns ({}), got {} (a frame "
                                    "received before the stage settled)",
                                    r.timing->settle_end_ns, r.first_timestamp_ns));
    }
    if (f.raw().contains("blackbody_readings") && !f.raw().at("blackbody_readings").is_null()) {
        r.blackbody_readings = readings_from_json(f.object("blackbody_readings"));
        if (r.kind == RecordKind::Polarizer)
            f.fail_here(f.field("blackbody_readings"), "expected none for a polarizer record");
    }
    if (f.raw().contains("audit") && !f.raw().at("audit").is_null())
        r.audit = audit_from_json(f.object("audit"), r.frames);
    check_record(f, r);
    return r;
}

}  // namespace

const char* to_string(FfcEvent::Kind kind) {
    return kind == FfcEvent::Kind::Scheduled ? "scheduled" : "detected";
}

namespace {
json ffc_event_to_json(const FfcEvent& e) {
    return json{
        {"kind", to_string(e.kind)},
        {"host_timestamp_ns", e.host_timestamp_ns},
        {"repeat", e.repeat},
        {"fpa_temperature_k", optional_number(e.fpa_temperature_k)},
        {"device_frame_count", e.device_frame_count ? json(*e.device_frame_count) : json(nullptr)},
        {"reason", e.reason}};
}

FfcEvent ffc_event_from_json(const Fields& f) {
    FfcEvent e;
    const std::string kind = f.string("kind");
    if (kind != "scheduled" && kind != "detected")
        f.fail_here(f.field("kind"),
                    fmt::format("expected \"scheduled\" or \"detected\", got \"{}\"", kind));
    e.kind = kind == "scheduled" ? FfcEvent::Kind::Scheduled : FfcEvent::Kind::Detected;
    e.host_timestamp_ns = f.integer("host_timestamp_ns", 0);
    e.repeat = static_cast<int>(f.integer("repeat", 0, std::numeric_limits<int>::max()));
    e.fpa_temperature_k = f.optional_number("fpa_temperature_k");
    if (!f.at("device_frame_count").is_null())
        e.device_frame_count = f.integer("device_frame_count", 0);
    e.reason = f.string("reason");
    return e;
}

json home_check_to_json(const HomeCheck& c) {
    return json{{"host_timestamp_ns", c.host_timestamp_ns},
                {"passed", c.passed},
                {"before_step", c.before_step},
                {"steps_since_last_good", c.steps_since_last_good}};
}

HomeCheck home_check_from_json(const Fields& f) {
    HomeCheck c;
    c.host_timestamp_ns = f.integer("host_timestamp_ns", 0);
    c.passed = f.boolean("passed");
    c.before_step = static_cast<int>(f.integer("before_step", 0, std::numeric_limits<int>::max()));
    c.steps_since_last_good = f.integer("steps_since_last_good", 0);
    return c;
}

/// v5's `camera.microgrid_pattern_deg`: absent (older sessions) or null for a plain camera, else
/// four distinct angles in [0, 180). That they determine S1 and S2 is checked where they are used
/// (calibration's MicrogridPattern).
std::optional<std::array<double, 4>> microgrid_pattern_from_json(const Fields& camera) {
    if (!camera.raw().contains("microgrid_pattern_deg")) return std::nullopt;
    const json& v = camera.raw().at("microgrid_pattern_deg");
    if (v.is_null()) return std::nullopt;
    const std::string field = camera.field("microgrid_pattern_deg");
    if (!v.is_array() || v.size() != 4)
        camera.fail_here(
            field, "expected null or an array of 4 angles in degrees, got " + Fields::describe(v));
    std::array<double, 4> angles{};
    for (std::size_t i = 0; i < 4; ++i) {
        if (!v[i].is_number() || !std::isfinite(v[i].get<double>()) || v[i].get<double>() < 0.0 ||
            v[i].get<double>() >= 180.0)
            camera.fail_here(fmt::format("{}[{}]", field, i),
                             "expected an angle in [0, 180) degrees, got " + v[i].dump());
        angles[i] = v[i].get<double>();
        for (std::size_t k = 0; k < i; ++k)
            if (angles[k] == angles[i])
                camera.fail_here(fmt::format("{}[{}]", field, i),
                                 fmt::format("{} repeats entry {}: expected four distinct angles",
                                             angles[i], k));
    }
    return angles;
}
}  // namespace

json session_to_json(const SessionManifest& m) {
    json planck = json::object();
    for (const auto& [k, v] : m.camera.planck_constants) planck[k] = v;
    json records = json::array();
    for (const auto& r : m.records) records.push_back(record_to_json(r));
    json ffc_events = json::array();
    for (const auto& e : m.ffc_events) ffc_events.push_back(ffc_event_to_json(e));
    json home_checks = json::array();
    for (const auto& c : m.home_checks) home_checks.push_back(home_check_to_json(c));
    return json{{"schema", kSessionSchema},
                {"schema_version", kSessionSchemaVersion},
                {"created_utc", m.created_utc},
                {"camera",
                 {{"uri", m.camera.uri},
                  {"vendor", m.camera.vendor},
                  {"model", m.camera.model},
                  {"serial", m.camera.serial},
                  {"pixel_format", m.camera.pixel_format},
                  {"width", m.camera.width},
                  {"height", m.camera.height},
                  {"bits_per_pixel", m.camera.bits_per_pixel},
                  {"frame_rate_hz", optional_number(m.camera.frame_rate_hz)},
                  {"planck_constants", planck},
                  {"microgrid_pattern_deg", m.camera.microgrid_pattern_deg
                                                ? json(*m.camera.microgrid_pattern_deg)
                                                : json(nullptr)}}},
                {"stage",
                 {{"uri", m.stage.uri},
                  {"vendor", m.stage.vendor},
                  {"model", m.stage.model},
                  {"serial", m.stage.serial},
                  {"firmware", m.stage.firmware},
                  {"counts_per_degree", m.stage.counts_per_degree}}},
                {"blackbody_controller", m.blackbody_controller
                                             ? json{{"uri", m.blackbody_controller->uri},
                                                    {"vendor", m.blackbody_controller->vendor},
                                                    {"model", m.blackbody_controller->model},
                                                    {"serial", m.blackbody_controller->serial},
                                                    {"firmware", m.blackbody_controller->firmware}}
                                             : json(nullptr)},
                {"plan", m.plan},
                {"metadata", m.metadata},
                {"records", records},
                {"ffc_events", ffc_events},
                {"home_checks", home_checks},
                {"complete", m.complete}};
}

SessionManifest session_from_json(const json& j, const std::string& source) {
    const Fields top(j, source, "");
    const std::string schema = top.string("schema");
    if (schema != kSessionSchema)
        top.fail_here("schema",
                      fmt::format("expected \"{}\", got \"{}\" (not a tirpol session manifest)",
                                  kSessionSchema, schema));
    const std::int64_t version = top.integer("schema_version", 1);
    if (version < kSessionSchemaOldestReadable || version > kSessionSchemaVersion)
        top.fail_here("schema_version",
                      fmt::format("expected {} to {}, got {} (written by a newer or older tirpol)",
                                  kSessionSchemaOldestReadable, kSessionSchemaVersion, version));
    SessionManifest m;
    m.schema_version = static_cast<int>(version);
    m.created_utc = top.string("created_utc");

    const Fields cam = top.object("camera");
    m.camera.uri = cam.string("uri");
    m.camera.vendor = cam.string("vendor");
    m.camera.model = cam.string("model");
    m.camera.serial = cam.string("serial");
    m.camera.pixel_format = cam.string("pixel_format");
    m.camera.width = static_cast<int>(cam.integer("width", 1, limits::kMaxImageSide));
    m.camera.height = static_cast<int>(cam.integer("height", 1, limits::kMaxImageSide));
    m.camera.bits_per_pixel = static_cast<int>(cam.integer("bits_per_pixel", 1, 64));
    m.camera.frame_rate_hz = cam.optional_number("frame_rate_hz");
    const Fields planck = cam.object("planck_constants");
    for (const auto& [k, v] : planck.raw().items()) m.camera.planck_constants[k] = planck.number(k);
    m.camera.microgrid_pattern_deg = microgrid_pattern_from_json(cam);

    const Fields stage = top.object("stage");
    m.stage.uri = stage.string("uri");
    m.stage.vendor = stage.string("vendor");
    m.stage.model = stage.string("model");
    m.stage.serial = stage.string("serial");
    m.stage.firmware = stage.string("firmware");
    m.stage.counts_per_degree = stage.number("counts_per_degree");
    if (!(m.stage.counts_per_degree > 0.0))
        stage.fail_here(
            stage.field("counts_per_degree"),
            fmt::format("expected a positive number, got {}", m.stage.counts_per_degree));

    if (top.raw().contains("blackbody_controller") &&
        !top.raw().at("blackbody_controller").is_null()) {
        const Fields bb = top.object("blackbody_controller");
        m.blackbody_controller =
            SessionBlackbodyController{bb.string("uri"), bb.string("vendor"), bb.string("model"),
                                       bb.string("serial"), bb.string("firmware")};
    }
    m.plan = top.object("plan").raw();
    m.metadata = top.object("metadata").raw();

    const json& records = top.at("records");
    if (!records.is_array())
        top.fail_here("records", "expected an array, got " + Fields::describe(records));
    std::set<std::string> files;
    for (std::size_t i = 0; i < records.size(); ++i) {
        const Fields rf(records[i], source, fmt::format("records[{}]", i));
        SessionRecord r = record_from_json(rf);
        if (!files.insert(r.file).second)
            rf.fail_here(rf.field("file"), "\"" + r.file + "\" is listed twice");
        m.records.push_back(std::move(r));
    }
    if (top.raw().contains("home_checks")) {
        const json& checks = top.at("home_checks");
        if (!checks.is_array())
            top.fail_here("home_checks", "expected an array, got " + Fields::describe(checks));
        for (std::size_t i = 0; i < checks.size(); ++i)
            m.home_checks.push_back(
                home_check_from_json(Fields(checks[i], source, fmt::format("home_checks[{}]", i))));
    }
    if (top.raw().contains("ffc_events")) {
        const json& events = top.at("ffc_events");
        if (!events.is_array())
            top.fail_here("ffc_events", "expected an array, got " + Fields::describe(events));
        for (std::size_t i = 0; i < events.size(); ++i)
            m.ffc_events.push_back(
                ffc_event_from_json(Fields(events[i], source, fmt::format("ffc_events[{}]", i))));
    }
    m.complete = top.boolean("complete");
    return m;
}

// ---- EXR header ⇄ record ------------------------------------------------------------------------

void record_to_attributes(const SessionRecord& r, Attributes& a) {
    a["tirpol_schema"] = std::string(kSessionSchema);
    a["kind"] = std::string(to_string(r.kind));
    a["angle_deg_requested"] = r.angle_deg_requested;
    a["angle_deg_measured"] = r.angle_deg_measured;
    a["repeat"] = r.repeat;
    if (r.blackbody_temperature_k)
        a["blackbody_temperature_k"] = *r.blackbody_temperature_k;
    else
        a.erase("blackbody_temperature_k");
    // Counts and timestamps go through text: EXR ints are 32-bit, doubles lose ns after 2^53.
    a["frames"] = std::to_string(r.frames);
    a["dropped"] = std::to_string(r.dropped);
    a["first_timestamp_ns"] = std::to_string(r.first_timestamp_ns);
    a["last_timestamp_ns"] = std::to_string(r.last_timestamp_ns);
    if (r.fpa_temperature_k)
        a["fpa_temperature_k"] = *r.fpa_temperature_k;
    else
        a.erase("fpa_temperature_k");
    const json timing = timing_to_json(r.timing.value_or(StepTiming{}));
    for (const auto& [key, value] : timing.items()) {
        const std::string name = "timing_" + key;
        if (!r.timing)
            a.erase(name);
        else if (value.is_number_integer())
            a[name] = std::to_string(value.get<std::int64_t>());
        else
            a[name] = value.get<double>();
    }
    const json readings = readings_to_json(r.blackbody_readings.value_or(BlackbodyReadings{}));
    for (const auto& [key, value] : readings.items()) {
        const std::string name = "blackbody_readings_" + key;
        if (!r.blackbody_readings)
            a.erase(name);
        else if (value.is_boolean())
            a[name] = value.get<bool>() ? 1 : 0;
        else if (value.is_number_integer())
            a[name] = std::to_string(value.get<std::int64_t>());
        else
            a[name] = value.get<double>();
    }
    a["units"] = std::string("counts");
}

SessionRecord record_from_attributes(const Attributes& a, const std::string& file,
                                     const std::string& source) {
    // Rebuild the JSON record from the header and validate it with the manifest's rules.
    json j = json::object();
    j["file"] = file;
    j["blackbody_temperature_k"] = nullptr;
    j["fpa_temperature_k"] = nullptr;
    for (const auto& [name, value] : a) {
        std::visit([&j, &key = name](const auto& v) { j[key] = v; }, value);
    }
    json timing = json::object();
    const json timing_keys = timing_to_json({});
    for (const auto& [key, unused] : timing_keys.items())
        if (auto it = j.find("timing_" + key); it != j.end()) {
            timing[key] = *it;
            j.erase(it);
        }
    if (!timing.empty()) j["timing"] = timing;
    json readings = json::object();
    const json readings_keys = readings_to_json({});  // named: items() of a temporary would dangle
    for (const auto& [key, unused] : readings_keys.items())
        if (auto it = j.find("blackbody_readings_" + key); it != j.end()) {
            readings[key] =
                key == "stable" && it->is_number_integer() ? json(it->get<int>() != 0) : *it;
            j.erase(it);
        }
    if (!readings.empty()) j["blackbody_readings"] = readings;
    auto decimal = [&source](json& holder, const std::string& key, const std::string& name) {
        auto it = holder.find(key);
        if (it == holder.end() || !it->is_string()) return;
        const std::string text = it->get<std::string>();
        char* end = nullptr;
        errno = 0;
        const long long v = std::strtoll(text.c_str(), &end, 10);
        if (text.empty() || *end != '\0' || errno != 0)
            fail("{}: header attribute {}: expected a decimal integer, got \"{}\"", source, name,
                 text);
        *it = static_cast<std::int64_t>(v);
    };
    for (const char* key : {"frames", "dropped", "first_timestamp_ns", "last_timestamp_ns"})
        decimal(j, key, key);
    if (j.contains("timing"))
        for (const char* key : {"move_start_ns", "move_end_ns", "settle_end_ns",
                                "exposure_window_ns", "stale_frames_discarded"})
            decimal(j["timing"], key, std::string("timing_") + key);
    if (j.contains("blackbody_readings"))
        decimal(j["blackbody_readings"], "readings", "blackbody_readings_readings");
    return record_from_json(Fields(j, source, "header"));
}

// ---- reading ------------------------------------------------------------------------------------

namespace {

SessionManifest read_manifest_file(const std::filesystem::path& dir) {
    const auto path = dir / kSessionManifestName;
    if (!std::filesystem::exists(path))
        fail("{}: no session manifest here (expected a directory written by tirpol acquire)",
             path.string());
    const std::string text = read_file(path);
    check_utf8_text(text, path.string());
    json j;
    try {
        j = json::parse(text);
    } catch (const json::parse_error& e) {
        fail("{}: not valid JSON (truncated or corrupt manifest?) at byte {} of {}: {}",
             path.string(), e.byte, text.size(), e.what());
    }
    return session_from_json(j, path.string());
}

/// Makes a new directory entry durable before the manifest that refers to it.
void fsync_directory(const std::filesystem::path& dir) {
    const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    ::fsync(fd);
    ::close(fd);
}

void check_frame_files_exist(const std::filesystem::path& dir, const SessionManifest& m) {
    for (std::size_t i = 0; i < m.records.size(); ++i) {
        const auto p = dir / m.records[i].file;
        std::error_code ec;
        if (!std::filesystem::is_regular_file(p, ec))
            fail("{}: records[{}].file: frame file {} is missing",
                 (dir / kSessionManifestName).string(), i, p.string());
    }
}

}  // namespace

SessionManifest read_session(const std::filesystem::path& dir) {
    SessionManifest m = read_manifest_file(dir);
    check_frame_files_exist(dir, m);
    return m;
}

namespace {
/// The frame's header mirrors its record and the camera (SessionWriter::add_record): where both say
/// something, they must agree, or a frame was filed under another record (renamed, copied, the
/// manifest edited) and would be reduced at the wrong angle or temperature.
void check_frame_header(const std::filesystem::path& path,
                        const std::filesystem::path& manifest_file, const SessionManifest& m,
                        const SessionRecord& r, const Attributes& a) {
    const auto number = [&a](const char* name) -> std::optional<double> {
        const auto it = a.find(name);
        if (it == a.end()) return std::nullopt;
        if (const double* d = std::get_if<double>(&it->second)) return *d;
        if (const int* i = std::get_if<int>(&it->second)) return *i;
        return std::nullopt;
    };
    const auto text = [&a](const char* name) -> std::optional<std::string> {
        const auto it = a.find(name);
        if (it == a.end()) return std::nullopt;
        if (const std::string* s = std::get_if<std::string>(&it->second)) return *s;
        return std::nullopt;
    };
    const auto disagree = [&](const std::string& field, const std::string& in_header,
                              const std::string& in_manifest) {
        fail(
            "{}: its header says {} = {} but {} files it as {} with {} = {}; the frame and the "
            "manifest disagree (a "
            "frame file renamed or copied, or the manifest edited): restore the session as it was "
            "written",
            path.string(), field, in_header, manifest_file.string(), r.file, field, in_manifest);
    };
    if (const auto kind = text("kind"); kind && *kind != to_string(r.kind))
        disagree("kind", *kind, to_string(r.kind));
    for (const auto& [name, value] :
         {std::pair<const char*, double>{"angle_deg_requested", r.angle_deg_requested},
          std::pair<const char*, double>{"angle_deg_measured", r.angle_deg_measured}})
        if (const auto v = number(name); v && std::abs(*v - value) > 1e-6)
            disagree(name, fmt::format("{:g}°", *v), fmt::format("{:g}°", value));
    if (const auto t = number("blackbody_temperature_k");
        t && r.blackbody_temperature_k && std::abs(*t - *r.blackbody_temperature_k) > 1e-6)
        disagree("blackbody_temperature_k", fmt::format("{:g} K", *t),
                 fmt::format("{:g} K", *r.blackbody_temperature_k));
    if (const auto serial = text("camera_serial"); serial && *serial != m.camera.serial)
        disagree("camera_serial", "'" + *serial + "'", "'" + m.camera.serial + "' (camera.serial)");
    const std::string model = m.camera.vendor + " " + m.camera.model;
    if (const auto header_model = text("camera_model"); header_model && *header_model != model)
        disagree("camera_model", "'" + *header_model + "'",
                 "'" + model + "' (camera.vendor, camera.model)");
}
}  // namespace

Image read_session_frame(const std::filesystem::path& dir, const SessionManifest& m,
                         const SessionRecord& r) {
    const auto path = dir / r.file;
    Image image = read_exr(path);
    for (const char* channel : {"counts", "counts_std"})
        if (!image.has_channel(channel))
            fail("{}: missing channel '{}' (a session frame has counts and counts_std)",
                 path.string(), channel);
    if (image.width() != m.camera.width || image.height() != m.camera.height)
        fail("{}: image is {}×{}, the manifest's camera is {}×{}", path.string(), image.width(),
             image.height(), m.camera.width, m.camera.height);
    check_frame_header(path, dir / kSessionManifestName, m, r, image.attributes());
    return image;
}

// ---- writing ------------------------------------------------------------------------------------

/// An exclusive flock on DIR/.lock; released when the process ends, even by SIGKILL.
struct SessionWriter::Lock {
    int fd = -1;
    explicit Lock(const std::filesystem::path& dir) {
        const auto path = dir / ".lock";
        fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
        if (fd < 0)
            fail("{}: cannot create the session lock: {}", path.string(), std::strerror(errno));
        if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
            ::close(fd);
            fail("{}: another process is writing this session", dir.string());
        }
    }
    ~Lock() {
        if (fd >= 0) ::close(fd);
    }
    Lock(const Lock&) = delete;
    Lock& operator=(const Lock&) = delete;
};

SessionWriter::SessionWriter(std::filesystem::path dir, SessionManifest manifest,
                             std::unique_ptr<Lock> lock)
    : m_dir(std::move(dir)), m_manifest(std::move(manifest)), m_lock(std::move(lock)) {}
SessionWriter::SessionWriter(SessionWriter&&) noexcept = default;
SessionWriter& SessionWriter::operator=(SessionWriter&&) noexcept = default;
SessionWriter::~SessionWriter() = default;

namespace {
/// A hidden sibling that create() builds a session in before renaming it into place.
std::string creating_prefix(const std::filesystem::path& dir) {
    return "." + dir.filename().string() + ".creating-";
}

/// Removes what earlier crashed create() calls for `dir` left: siblings nobody holds the lock of.
void remove_abandoned_creations(const std::filesystem::path& dir) {
    std::error_code ec;
    const auto parent = dir.parent_path().empty() ? std::filesystem::path(".") : dir.parent_path();
    const std::string prefix = creating_prefix(dir);
    for (const auto& entry : std::filesystem::directory_iterator(parent, ec)) {
        if (entry.path().filename().string().rfind(prefix, 0) != 0) continue;
        const int fd = ::open((entry.path() / ".lock").c_str(), O_RDWR | O_CLOEXEC);
        const bool abandoned = fd < 0 || ::flock(fd, LOCK_EX | LOCK_NB) == 0;
        if (fd >= 0) ::close(fd);
        if (abandoned) std::filesystem::remove_all(entry.path(), ec);
    }
}
}  // namespace

SessionWriter SessionWriter::create(const std::filesystem::path& dir_in, SessionManifest manifest) {
    const std::filesystem::path dir = dir_in.has_filename() ? dir_in : dir_in.parent_path();
    std::error_code ec;
    if (std::filesystem::exists(dir, ec)) {
        if (!std::filesystem::is_directory(dir, ec))
            fail("{}: exists and is not a directory", dir.string());
        if (!std::filesystem::is_empty(dir, ec))
            fail(
                "{}: directory exists and is not empty; refusing to start a new session there "
                "(use --resume to continue a session, or choose a new directory)",
                dir.string());
    }
    if (dir.has_parent_path()) {
        std::filesystem::create_directories(dir.parent_path(), ec);
        if (ec) fail("{}: cannot create the parent directory: {}", dir.string(), ec.message());
    }
    if (manifest.created_utc.empty()) manifest.created_utc = utc_now_iso8601();
    manifest.schema_version = kSessionSchemaVersion;
    manifest.records.clear();
    manifest.complete = false;
    // Validate what the caller gave before anything is created.
    session_from_json(session_to_json(manifest), (dir / kSessionManifestName).string());
    remove_abandoned_creations(dir);

    // Build the whole empty session beside `dir`, then rename it into place: rename(2) replaces an
    // empty directory atomically, so `dir` is never seen half made.
    const auto staging = dir.parent_path() / (creating_prefix(dir) + std::to_string(::getpid()));
    std::filesystem::remove_all(staging, ec);
    struct Cleanup {
        std::filesystem::path path;
        bool armed = true;
        ~Cleanup() {
            std::error_code e;
            if (armed) std::filesystem::remove_all(path, e);
        }
    } cleanup{staging};
    std::filesystem::create_directories(staging / "frames", ec);
    if (ec) fail("{}: cannot create the session directory: {}", dir.string(), ec.message());
    auto lock = std::make_unique<Lock>(staging);  // the flock stays on the inode across the rename
    write_file_atomic(staging / kSessionManifestName, session_to_json(manifest).dump(2) + "\n");
    fsync_directory(staging);
    if (::rename(staging.c_str(), dir.c_str()) != 0) {
        const int err = errno;
        if (err == ENOTEMPTY || err == EEXIST)
            fail(
                "{}: another session appeared here while this one was being created; refusing to "
                "mix them",
                dir.string());
        fail("{}: cannot move the new session into place: {}", dir.string(), std::strerror(err));
    }
    cleanup.armed = false;
    fsync_directory(dir.parent_path().empty() ? std::filesystem::path(".") : dir.parent_path());
    return SessionWriter(dir, std::move(manifest), std::move(lock));
}

SessionWriter SessionWriter::resume(const std::filesystem::path& dir) {
    auto lock = std::make_unique<Lock>(dir);
    SessionManifest manifest = read_manifest_file(dir);
    if (manifest.schema_version < 2)
        fail(
            "{}: a schema v{} session (written before frames were gated on the end of each move); "
            "it reads, "
            "but resuming would mix two timing models: finish it with the tirpol that started it, "
            "or start a new session",
            (dir / kSessionManifestName).string(), manifest.schema_version);
    check_frame_files_exist(dir, manifest);
    SessionWriter writer(dir, std::move(manifest), std::move(lock));
    std::error_code ec;
    // Manifest temporaries of an interrupted atomic write (write_file_atomic's
    // ".session.json.tmp-*").
    const std::string manifest_tmp = std::string(".") + kSessionManifestName + ".tmp-";
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        if (entry.path().filename().string().rfind(manifest_tmp, 0) == 0)
            std::filesystem::remove(entry.path(), ec);
    const auto frames = dir / "frames";
    std::filesystem::create_directories(frames, ec);
    std::vector<std::filesystem::path> candidates;
    for (const auto& entry : std::filesystem::directory_iterator(frames)) {
        if (!entry.is_regular_file()) continue;
        const std::string name = entry.path().filename().string();
        // Temporary files of an interrupted write hold nothing committed: remove them.
        if (!name.empty() && name.front() == '.') {
            std::filesystem::remove(entry.path(), ec);
            continue;
        }
        if (entry.path().extension() == ".exr" && !writer.has_record("frames/" + name))
            candidates.push_back(entry.path());
    }
    std::sort(candidates.begin(), candidates.end());
    for (const auto& path : candidates) {
        const std::string file = "frames/" + path.filename().string();
        const Image image = read_exr(path);
        SessionRecord r = record_from_attributes(image.attributes(), file, path.string());
        writer.m_manifest.records.push_back(std::move(r));
        writer.m_adopted.push_back(file);
    }
    if (!candidates.empty()) writer.write_manifest();
    return writer;
}

bool SessionWriter::has_record(const std::string& file) const {
    for (const auto& r : m_manifest.records)
        if (r.file == file) return true;
    return false;
}

void SessionWriter::add_record(const SessionRecord& record, const Image& frame) {
    const std::string source = (m_dir / kSessionManifestName).string();
    if (m_manifest.complete)
        fail("{}: the session is complete; refusing to add {}", source, record.file);
    // Validate the record as the reader will.
    record_from_json(Fields(record_to_json(record), source, "new record"));
    if (has_record(record.file))
        fail("{}: {} is already recorded; refusing to overwrite it", source, record.file);
    for (const char* channel : {"counts", "counts_std"})
        if (!frame.has_channel(channel))
            fail("{}: frame for {} lacks channel '{}'", source, record.file, channel);
    if (frame.width() != m_manifest.camera.width || frame.height() != m_manifest.camera.height)
        fail("{}: frame for {} is {}×{}, the camera is {}×{}", source, record.file, frame.width(),
             frame.height(), m_manifest.camera.width, m_manifest.camera.height);

    Image annotated = frame;
    record_to_attributes(record, annotated.attributes());
    annotated.attributes()["camera_uri"] = m_manifest.camera.uri;
    annotated.attributes()["camera_model"] =
        m_manifest.camera.vendor + " " + m_manifest.camera.model;
    annotated.attributes()["camera_serial"] = m_manifest.camera.serial;
    annotated.attributes()["stage_uri"] = m_manifest.stage.uri;
    annotated.attributes()["stage_model"] = m_manifest.stage.vendor + " " + m_manifest.stage.model;
    annotated.attributes()["stage_serial"] = m_manifest.stage.serial;

    // write_exr renames over its destination; to never overwrite, write a hidden file and hard-link
    // it into place: link() fails with EEXIST instead of replacing.
    const auto final_path = m_dir / record.file;
    const auto staged =
        final_path.parent_path() / fmt::format(".{}.staged.exr", final_path.filename().string());
    write_exr(staged, annotated);
    if (::link(staged.c_str(), final_path.c_str()) != 0) {
        const int err = errno;
        std::error_code ec;
        std::filesystem::remove(staged, ec);
        if (err == EEXIST)
            fail("{}: {} already exists on disk; refusing to overwrite it", source,
                 final_path.string());
        fail("{}: cannot place {}: {}", source, final_path.string(), std::strerror(err));
    }
    std::error_code ec;
    std::filesystem::remove(staged, ec);
    fsync_directory(final_path.parent_path());
    m_manifest.records.push_back(record);
    write_manifest();
}

void SessionWriter::set_camera_frame_rate(double frame_rate_hz) {
    if (!(frame_rate_hz > 0.0) || !std::isfinite(frame_rate_hz))
        fail("{}: camera.frame_rate_hz: expected a measured rate > 0 Hz, got {}",
             (m_dir / kSessionManifestName).string(), frame_rate_hz);
    m_manifest.camera.frame_rate_hz = frame_rate_hz;
}

void SessionWriter::add_ffc_event(const FfcEvent& event) {
    m_manifest.ffc_events.push_back(event);
    write_manifest();
}

void SessionWriter::add_home_check(const HomeCheck& check) {
    m_manifest.home_checks.push_back(check);
    write_manifest();
}

void SessionWriter::set_metadata(nlohmann::json metadata) {
    m_manifest.metadata = std::move(metadata);
    write_manifest();
}

void SessionWriter::mark_complete() {
    m_manifest.complete = true;
    write_manifest();
}

void SessionWriter::write_manifest() const {
    write_file_atomic(m_dir / kSessionManifestName,
                      json_text(session_to_json(m_manifest), 2) + "\n");
}

}  // namespace tirpol
