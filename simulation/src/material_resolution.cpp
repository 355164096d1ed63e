#include "material_resolution.h"

#include "tirpol/core/error.h"
#include "tirpol/materials/material.h"

namespace tirpol::simulation::detail {

MaterialResolver::MaterialResolver(std::filesystem::path materials_dir)
    : m_dir(std::move(materials_dir)) {}

namespace {
bool looks_like_path(const std::string& s) {
    return s.find('/') != std::string::npos || s.ends_with(".yaml") || s.ends_with(".yml");
}

/// Library file of a material name: "<dir>/<name>.yaml" (or .yml); library files are named after
/// their material (config/materials/). Empty if none.
std::filesystem::path library_file(const std::filesystem::path& dir, const std::string& name) {
    for (const char* ext : {".yaml", ".yml"}) {
        const auto p = dir / (name + ext);
        if (std::filesystem::is_regular_file(p)) return p;
    }
    return {};
}
}  // namespace

std::uint32_t MaterialResolver::resolve(const ConfigNode& node,
                                        std::vector<SceneMaterial>& materials) {
    std::string key;
    if (node.is_map())
        key = "inline@" + node.location();
    else if (const std::string ref = node.as<std::string>(); looks_like_path(ref))
        key = "file@" + std::filesystem::weakly_canonical(node.resolve_path(ref)).string();
    else
        key = "name@" + ref;
    if (auto it = m_seen.find(key); it != m_seen.end()) return it->second;

    materials::Material material;
    if (node.is_map()) {
        material = materials::material_from_config(node, "inline_" + node.path());
    } else if (const std::string ref = node.as<std::string>(); looks_like_path(ref)) {
        const auto path = node.resolve_path(ref);
        if (!std::filesystem::is_regular_file(path))
            node.fail("material file not found: " + path.string());
        material = materials::load_material(path);
    } else if (const auto path = library_file(m_dir, ref); !path.empty()) {
        material = materials::load_material(path);
    } else {
        // No file of that name: the library may still define it under another file name.
        if (!std::filesystem::is_directory(m_dir))
            node.fail(fmt::format(
                "unknown material \"{}\": materials directory {} not found (set materials_dir)",
                ref, m_dir.string()));
        const auto library = materials::MaterialLibrary::load_directory(m_dir);
        if (!library.contains(ref))
            node.fail(fmt::format("unknown material \"{}\" (not in {}; known: {})", ref,
                                  m_dir.string(), fmt::join(library.names(), ", ")));
        material = library.get(ref);
    }
    const auto index = static_cast<std::uint32_t>(materials.size());
    materials.push_back(SceneMaterial{
        material.name, material.file.empty() ? node.location() : material.file.string(),
        material.brdf});
    m_seen.emplace(key, index);
    return index;
}

}  // namespace tirpol::simulation::detail
