#pragma once
// OUT/manifest.json: the sweep's inputs and every point's parameters, seed, status and error
// (private).

#include <filesystem>

#include "tirpol/sweep/sweep_run.h"

namespace tirpol::sweep::detail {

/// Writes the manifest atomically (points sorted by index).
void write_manifest(const std::filesystem::path& path, const SweepSpec& spec,
                    const SweepSummary& summary);

/// Throws tirpol::Error unless the manifest at `path` lists the same points (ids, parameters,
/// seeds): resuming a different sweep into the same folder would mix two studies.
void check_same_sweep(const std::filesystem::path& path, const SweepSpec& spec,
                      const std::vector<SweepPoint>& points);

}  // namespace tirpol::sweep::detail
