#pragma once
/// \file material_reference.h
/// A material named on a command line the way scenes name them: a file or a library name.

#include <filesystem>
#include <string>

namespace tirpol::materials {

/// The file a material argument names: a YAML file (any path with a '/' or ending in .yaml/.yml, or
/// an existing file), or else a library name resolved to config/materials/<name>.yaml
/// (find_config). Throws tirpol::Error naming a missing file, or an unknown name with the closest
/// library name and the list of names.
std::filesystem::path material_file(const std::string& name_or_path);

}  // namespace tirpol::materials
