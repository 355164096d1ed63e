#pragma once
/// \file session_summary.h
/// What a reviewer wants to know of a capture session at a glance (`tirpol info SESSION`): its
/// records and frames, what the camera lost, the per-frame audit, the camera core's flat-field
/// corrections and the stage's lost-step checks. Computed from the manifest alone (session.h).

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

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

}  // namespace tirpol
