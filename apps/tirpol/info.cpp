// `tirpol info FILE.exr`: size, channels, header attributes and per-channel statistics.
// `tirpol info SESSION`: a capture session's summary (records, audit, FFCs, lost-step checks).

#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/session_summary.h"
#include "tirpol/core/utf8.h"

namespace tirpol::cli {

namespace {
nlohmann::json attribute_json(const AttributeValue& v) {
    return std::visit([](const auto& x) { return nlohmann::json(x); }, v);
}

std::string attribute_text(const AttributeValue& v) {
    return std::visit(
        [](const auto& x) -> std::string {
            using T = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<T, std::string>)
                return "\"" + x + "\"";
            else if constexpr (std::is_same_v<T, std::vector<double>>)
                return json_text(nlohmann::json(x));
            else
                return fmt::format("{}", x);
        },
        v);
}

nlohmann::json finite_or_null(double v) {
    return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

std::string utc_text(std::int64_t host_ns) {
    const std::time_t seconds = static_cast<std::time_t>(host_ns / 1'000'000'000);
    std::tm utc{};
    gmtime_r(&seconds, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return text;
}

void run_session_info(const std::string& dir, bool json) {
    const SessionSummary s = summarize_session(read_session(dir));
    if (json) {
        nlohmann::json out = session_summary_to_json(s);
        out["session"] = dir;
        std::printf("%s\n", json_text(out, 2).c_str());
        return;
    }
    std::printf("%s: capture session, schema v%d, %s, created %s\n", dir.c_str(), s.schema_version,
                s.complete ? "complete" : "incomplete", s.created_utc.c_str());
    std::printf("  camera %s, stage %s\n", s.camera_uri.c_str(), s.stage_uri.c_str());
    std::printf("  records: %zu (%zu polarizer, %zu reference), %lld frames averaged\n", s.records,
                s.polarizer_records, s.reference_records, static_cast<long long>(s.frames));
    std::printf("  camera losses: %lld dropped, %lld incomplete\n",
                static_cast<long long>(s.dropped), static_cast<long long>(s.incomplete));
    std::printf(
        "  audit: %zu of %zu records per frame; %lld frames with a device clock, %lld with the "
        "core's telemetry, %lld kept during an FFC\n",
        s.audited_records, s.records, static_cast<long long>(s.frames_with_device_clock),
        static_cast<long long>(s.frames_with_core_telemetry),
        static_cast<long long>(s.frames_during_ffc));
    if (s.fpa_min_k) std::printf("  FPA temperature: %.2f to %.2f K\n", *s.fpa_min_k, *s.fpa_max_k);
    std::printf(
        "  flat-field corrections: %d scheduled between cycles, %d detected inside a cycle\n",
        s.ffc_scheduled, s.ffc_detected);
    std::printf("  lost-step checks at the home sensor: %d passed, %d failed\n",
                s.home_checks_passed, s.home_checks_failed);
    for (const auto& c : s.home_checks)
        std::printf("    before step %d: %s, %lld steps since the last good check, at %s\n",
                    c.before_step + 1, c.passed ? "passed" : "FAILED (lost steps)",
                    static_cast<long long>(c.steps_since_last_good),
                    utc_text(c.host_timestamp_ns).c_str());
}

void run_info(const std::string& path, bool json) {
    if (std::filesystem::is_directory(path)) {
        run_session_info(path, json);
        return;
    }
    const Image image = read_exr(path);
    nlohmann::json out;
    out["file"] = path;
    out["width"] = image.width();
    out["height"] = image.height();
    for (const auto& [name, value] : image.attributes())
        out["attributes"][name] = attribute_json(value);
    for (const auto& name : image.channel_names()) {
        const ChannelStats s = channel_stats(image.channel(name));
        out["channels"][name] = {{"min", finite_or_null(s.min)}, {"mean", finite_or_null(s.mean)},
                                 {"max", finite_or_null(s.max)}, {"std", finite_or_null(s.std)},
                                 {"nan_count", s.nan_count},     {"inf_count", s.inf_count}};
    }
    if (json) {
        std::printf("%s\n", json_text(out, 2).c_str());
        return;
    }
    std::printf("%s: %d × %d, %zu channel(s)\n", path.c_str(), image.width(), image.height(),
                image.channel_names().size());
    if (!image.attributes().empty()) std::printf("attributes:\n");
    for (const auto& [name, value] : image.attributes())
        std::printf("  %-28s %s\n", name.c_str(), attribute_text(value).c_str());
    std::printf("%-12s %14s %14s %14s %12s %8s\n", "channel", "min", "mean", "max", "std", "NaN");
    for (const auto& name : image.channel_names()) {
        const ChannelStats s = channel_stats(image.channel(name));
        std::printf("%-12s %14.6g %14.6g %14.6g %12.4g %8zu\n", name.c_str(), s.min, s.mean, s.max,
                    s.std, s.nan_count);
    }
}
}  // namespace

namespace {
void register_info(CLI::App& app) {
    auto path = std::make_shared<std::string>();
    auto json = std::make_shared<bool>(false);
    auto* cmd =
        app.add_subcommand("info",
                           "Describe an EXR image (size, channels, header, statistics) or a "
                           "capture session directory (records, audit, FFCs, lost-step checks)");
    cmd->add_option("FILE", *path, "OpenEXR file or session directory")->required();
    cmd->add_flag("--json", *json, "Print JSON");
    cmd->callback([path, json] { run_info(*path, *json); });
}

}  // namespace

TIRPOL_REGISTER_COMMAND(10, register_info);

}  // namespace tirpol::cli
