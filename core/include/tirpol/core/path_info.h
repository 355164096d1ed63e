#pragma once
/// \file path_info.h
/// `tirpol info PATH`: what an OpenEXR file holds (size, header attributes, per-channel statistics)
/// or, for a directory, the summary of the capture session in it; JSON and text formats.
///
/// What a reviewer wants to know of a capture session at a glance (`tirpol info SESSION`): its
/// records and frames, what the camera lost, the per-frame audit, the camera core's flat-field
/// corrections and the stage's lost-step checks. Computed from the manifest alone (session.h).

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "tirpol/core/image.h"
#include "tirpol/core/session.h"

namespace tirpol {

struct SessionSummary {
    int schema_version = 0;
    bool complete = false;
    std::string created_utc, camera_uri, stage_uri;
    std::size_t records = 0, polarizer_records = 0, reference_records = 0;
    std::int64_t frames = 0;      ///< frames averaged into the records
    std::int64_t dropped = 0;     ///< frames the camera lost while the records' frames were taken
    std::int64_t incomplete = 0;  ///< damaged frames the camera discarded (audited records)
    std::size_t audited_records = 0;  ///< records with a per-frame audit (schema v4 on)
    /// Audited frames with a device timestamp, and with the core's own telemetry (v6).
    std::int64_t frames_with_device_clock = 0, frames_with_core_telemetry = 0;
    /// Kept frames whose telemetry says an FFC was imminent or in progress (should be 0).
    std::int64_t frames_during_ffc = 0;
    std::optional<double> fpa_min_k, fpa_max_k;  ///< over the audited frames that report one
    int ffc_scheduled = 0, ffc_detected = 0;
    std::vector<HomeCheck> home_checks;  ///< as recorded, in order
    int home_checks_passed = 0, home_checks_failed = 0;
};

/// Counts what the manifest holds.
SessionSummary summarize_session(const SessionManifest& manifest);

/// The summary as JSON (`tirpol info SESSION --json`): the fields above under their names.
nlohmann::json session_summary_to_json(const SessionSummary& summary);

/// The summary as text (`tirpol info SESSION`), headed by the session directory `dir`: records,
/// losses, audit, FPA range, flat-field corrections and every lost-step check with its UTC time.
std::string session_summary_text(const SessionSummary& summary, const std::string& dir);

/// An OpenEXR file's size, header and the statistics of each channel.
struct ImageInfo {
    int width = 0, height = 0;
    Attributes attributes;
    std::vector<std::pair<std::string, ChannelStats>> channels;  ///< in the file's order
};

/// What describe_path found: exactly one of image and session is set.
struct PathInfo {
    std::string path;
    std::optional<ImageInfo> image;
    std::optional<SessionSummary> session;
};

/// A directory is read as a capture session (read_session, summarize_session), anything else as
/// an OpenEXR file. Throws tirpol::Error naming the path when it does not read.
PathInfo describe_path(const std::string& path);

/// The JSON description: for an image file, width, height, attributes and channels (min, mean,
/// max, std, nan_count, inf_count; non-finite statistics as null); for a session, its summary
/// (session_summary_to_json) with "session": the path.
nlohmann::json path_info_json(const PathInfo& info);

/// The text description: a heading, the attributes and a table of channel statistics, or
/// session_summary_text.
std::string path_info_text(const PathInfo& info);

}  // namespace tirpol
