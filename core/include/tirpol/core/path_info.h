#pragma once
/// \file path_info.h
/// `tirpol info PATH`: what an OpenEXR file holds (size, header attributes, per-channel statistics)
/// or, for a directory, the summary of the capture session in it; JSON and text formats.
///
/// What a reviewer wants to know of a capture session at a glance (`tirpol info SESSION`): its
/// records and frames, what the camera lost, the per-frame audit, the camera core's flat-field
/// corrections and the stage's lost-step checks. Computed from the manifest alone (session.h).
///
/// `tirpol planck`: a blackbody's band radiance and dL/dT at a temperature, or the brightness
/// temperature of a band radiance, and the two formats of the answer (JSON, text).

#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "tirpol/core/image.h"
#include "tirpol/core/radiometry.h"
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

/// The question: one of temperature_k or radiance_w_m2_sr, in the band band_um (with the RSR file
/// named by rsr, empty for a flat response).
struct PlanckQuery {
    std::array<double, 2> band_um{};
    std::string rsr;  ///< the RSR CSV as given, reported back; "" = none
    std::optional<double> temperature_k;
    std::optional<double> radiance_w_m2_sr;
};

/// The answer of evaluate_planck: radiance and its derivative for a temperature, or the brightness
/// temperature for a radiance.
struct PlanckAnswer {
    PlanckQuery query;
    double radiance_w_m2_sr = 0.0;
    std::optional<double> radiance_dT_w_m2_sr_k;     ///< for a temperature
    std::optional<double> brightness_temperature_k;  ///< for a radiance
};

/// Evaluates `query` with `band` (built from query.band_um and the RSR). Throws
/// tirpol::OptionValueError naming --temperature-k for a temperature outside the physical range or
/// --radiance for a radiance that is not positive, tirpol::Error for a query with neither or both,
/// or a result that is not finite.
PlanckAnswer evaluate_planck(const Band& band, const PlanckQuery& query);

/// `tirpol planck`: evaluates `query` in the band its band_um and rsr (a CSV file, read) make.
/// Throws tirpol::OptionValueError naming --band-um for band limits Band refuses, tirpol::Error for
/// an RSR file that does not read, and what the overload above throws.
PlanckAnswer evaluate_planck(const PlanckQuery& query);

/// The JSON answer (docs/cli.md): band_um, rsr (null when none), temperature_k,
/// radiance_w_m2_sr, radiance_dT_w_m2_sr_k or radiance_w_m2_sr, brightness_temperature_k.
nlohmann::json planck_answer_json(const PlanckAnswer& answer);

/// The text answer, one line per quantity.
std::string planck_answer_text(const PlanckAnswer& answer);

}  // namespace tirpol
