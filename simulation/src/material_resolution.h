#pragma once
// Resolves the `material:` field of a scene object to a pBRDF (private to the loader).

#include <filesystem>
#include <map>
#include <memory>

#include "tirpol/core/config.h"
#include "tirpol/simulation/scene.h"

namespace tirpol::simulation::detail {

/// Resolves names against the material library in `materials_dir`, paths relative to the scene
/// file, inline mappings in place. Identical references share one SceneMaterial (deduplicated by
/// key).
class MaterialResolver {
public:
    explicit MaterialResolver(std::filesystem::path materials_dir);
    /// Index of the material in `materials`, appending it if new.
    std::uint32_t resolve(const ConfigNode& node, std::vector<SceneMaterial>& materials);

private:
    std::filesystem::path m_dir;
    std::map<std::string, std::uint32_t> m_seen;
};

}  // namespace tirpol::simulation::detail
