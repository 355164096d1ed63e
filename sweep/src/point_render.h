#pragma once
// Rendering one sweep point into its folder, and reading back a finished one (private).

#include <filesystem>
#include <optional>

#include "tirpol/sweep/sweep_run.h"

namespace tirpol::sweep::detail {

/// Renders `point` into `out_dir`/points/<id>/ through a temporary folder renamed when complete.
/// Never throws for a problem of the point (scene error, render error, unwritable file): the record
/// says "failed" with the message.
PointRecord render_point(const SweepSpec& spec, const SweepPoint& point,
                         const std::filesystem::path& out_dir, int threads);

/// The statistics of a point finished by an earlier run (its folder exists), else nullopt.
std::optional<PointStatistics> finished_point(const std::filesystem::path& out_dir,
                                              const SweepPoint& point);

}  // namespace tirpol::sweep::detail
