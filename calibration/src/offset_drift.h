#pragma once
/// \file offset_drift.h
/// Offset drift of an uncooled camera *during* a session (docs/calibration.md, "Drift correction in
/// a session"): a uniform offset shift in counts, measured at reference instants and applied to
/// every scene record. References are either
/// - an in-scene reference blackbody region: plan `scene_reference` {roi: {x, y, width, height},
///   temperature_k (contact sensor), temperature_sigma_k}; seen in every scene record through the
///   polarizer, so each record carries its own reference at its own time; or
/// - temperature-tagged shutter (flat-field) records interleaved with the scene records: the shift
///   of a scene record is interpolated linearly in time between the two nearest of them.
/// A shift is mean(counts − model counts of the expected radiance) over the reference pixels, with
/// the calibration at the record's FPA temperature; its σ combines the frame-mean noise of those
/// pixels and the reference temperature's σ.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/calibration/radiometric.h"
#include "tirpol/core/session.h"

namespace tirpol::calibration {

/// An in-scene reference blackbody: where it is in the image and its temperature.
struct SceneReferenceRegion {
    int x = 0, y = 0, width = 0, height = 0;  ///< pixels, top-left corner and size
    double temperature_k = 0.0;               ///< contact sensor (or controller) reading
    double temperature_sigma_k = 0.0;         ///< its uncertainty (1 σ)
};

/// The session plan's `scene_reference`, if any; throws tirpol::Error naming the manifest and field
/// when it is malformed or the ROI leaves the image.
std::optional<SceneReferenceRegion> scene_reference_region(const std::filesystem::path& dir,
                                                           const SessionManifest& manifest);

/// The offset shift at one instant.
struct OffsetDriftPoint {
    double time_s = 0.0;        ///< mid-time of the record's frames, s since the epoch
    double shift_counts = 0.0;  ///< counts to subtract (measured − model)
    double sigma_counts = 0.0;  ///< 1 σ of shift_counts
};

/// The shift at `time_s`, linear between the neighbouring points (sorted by time, ≥ 1), held
/// constant outside them; σ combines the neighbours' σ with the interpolation weights.
OffsetDriftPoint interpolate_offset_drift(const std::vector<OffsetDriftPoint>& points,
                                          double time_s);

/// Measures the shift from a record's `counts` / `counts_std` (frames averaged: `frames`) over
/// `pixels` (indices; bad pixels of `cal` skipped), where the radiance seen is
/// `expected_radiance` ± `radiance_sigma`. `cal` is at the record's FPA temperature.
OffsetDriftPoint measure_offset_drift(const RadiometricCalibration& cal,
                                      const std::vector<float>& counts,
                                      const std::vector<float>& counts_std, std::int64_t frames,
                                      const std::vector<std::size_t>& pixels,
                                      double expected_radiance, double radiance_sigma,
                                      double time_s, const std::string& what);

/// The drift correction of each scene (polarizer) record of a session, in record order.
struct SessionOffsetDrift {
    std::string source;  ///< "scene_reference ..." or "shutter records ..."
    std::vector<std::string> files;
    std::vector<OffsetDriftPoint> points;  ///< one per file, at the record's time
};

/// From the plan's scene_reference when present, else from the temperature-tagged shutter records.
/// Throws tirpol::Error naming the manifest when the session has neither.
SessionOffsetDrift session_offset_drift(const std::filesystem::path& dir,
                                        const SessionManifest& manifest,
                                        const RadiometricCalibration& cal);

}  // namespace tirpol::calibration
