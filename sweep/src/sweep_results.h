#pragma once
/// \file sweep_results.h
/// What a person looks at after a sweep (written by rank 0 into OUT):
/// - results.csv / results.json: one row per point — index, id, status, each axis's value, seed,
/// then
///   for every region and contrast the mean and Monte-Carlo error of S0, S1, S2, DoLP,
///   temperature_k (columns `<region>.<quantity>` and `<region>.<quantity>.error`; empty for a
///   failed point);
/// - plots/<axis>_<quantity>.png: each region (solid) and contrast (dashed) against each axis with
///   two or more values, the other axes held at their first value;
/// - contact_sheet_S0.png, contact_sheet_S1.png: every point's image on one common colour range,
///   labelled with its id and values (tiles in tiles/);
/// - for a `time` axis, animation/: frames frame_000.png… (S0 | S1 side by side, in time order, the
///   other axes at their first value) and index.html, a page that plays them (no server needed).

#include <filesystem>
#include <vector>

#include "tirpol/sweep/sweep_run.h"

namespace tirpol::sweep {

/// Writes the files above from the points' records (statistics) and their folders (images); returns
/// the paths written.
std::vector<std::filesystem::path> write_results(const SweepSpec& spec,
                                                 const std::filesystem::path& out_dir,
                                                 const std::vector<PointRecord>& points);

/// Indices of the points on the line through the first point along axis `axis`: every other axis at
/// its first value (grid), or all points (list).
std::vector<std::size_t> points_along(const SweepSpec& spec, const std::vector<PointRecord>& points,
                                      std::size_t axis);

}  // namespace tirpol::sweep
