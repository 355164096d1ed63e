#pragma once
/// \file render_output.h
/// Writing a rendered Stokes image: the EXR (all channels and header attributes) and PNG quicklooks
/// of S0, S1, S2, DoLP, AoP and temperature.

#include <filesystem>
#include <string>
#include <vector>

#include "tirpol/core/image.h"

namespace tirpol::simulation {

/// Writes `<out_dir>/<stem>.exr` and `<out_dir>/<stem>_<channel>.png` for the quicklook channels;
/// returns the paths written. Atomic writes; creates `out_dir`.
std::vector<std::filesystem::path> write_render_outputs(const std::filesystem::path& out_dir,
                                                        const std::string& stem,
                                                        const Image& image);

}  // namespace tirpol::simulation
