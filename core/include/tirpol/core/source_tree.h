#pragma once
/// \file source_tree.h
/// Finding the repository's config/ folder (material library, scenes, thermal examples) from the
/// demo, the benchmarks and other programs run inside or below the source tree, or installed
/// (`cmake --install`).

#include <filesystem>

namespace tirpol {

/// Absolute path of `config/<relative>` (a file or folder), searched in the working directory, the
/// executable's directory and each of their parents (the source tree); then in an installed tree:
/// `<prefix>/share/tirpol/config/<relative>` above the executable or the shared object (the Python
/// extension) this code was loaded from, and finally under the install prefix configured at build
/// time. Throws tirpol::Error naming what was looked for.
std::filesystem::path find_config(const std::filesystem::path& relative);

}  // namespace tirpol
