#pragma once
// The parts of write_results (sweep_results.h), one file each (private).

#include <filesystem>
#include <vector>

#include "sweep_results.h"

namespace tirpol::sweep::detail {

std::vector<std::filesystem::path> write_tables(const SweepSpec& spec,
                                                const std::filesystem::path& out_dir,
                                                const std::vector<PointRecord>& points);
std::vector<std::filesystem::path> write_axis_plots(const SweepSpec& spec,
                                                    const std::filesystem::path& out_dir,
                                                    const std::vector<PointRecord>& points);
/// Contact sheets and, with a `time` axis, the animation.
std::vector<std::filesystem::path> write_image_summaries(const SweepSpec& spec,
                                                         const std::filesystem::path& out_dir,
                                                         const std::vector<PointRecord>& points);

}  // namespace tirpol::sweep::detail
