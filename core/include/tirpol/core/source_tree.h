#pragma once
/// \file source_tree.h
/// Finding the repository's config/ folder (material library, scenes, thermal examples) from the demo,
/// the benchmarks and other programs run inside or below the source tree.

#include <filesystem>

namespace tirpol {

/// Absolute path of `config/<relative>` (a file or folder), searched in the working directory, the
/// executable's directory and each of their parents. Throws tirpol::Error naming what was looked for.
std::filesystem::path find_config(const std::filesystem::path& relative);

}  // namespace tirpol
