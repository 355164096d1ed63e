#include "tirpol/materials/material.h"

#include <algorithm>

#include "brdf_registry.h"
#include "tirpol/core/config.h"
#include "tirpol/core/error.h"

namespace tirpol::materials {

Material material_from_config(const ConfigNode& node, const std::string& fallback_name) {
    if (!node.is_map()) node.fail("expected a material mapping (name, source, model, ...)");
    // Thermal properties live with the slab solver's layered materials, not here
    // (docs/materials.md).
    if (node.has("thermal"))
        node.at("thermal").fail(
            "a material file no longer carries `thermal`: give the layers (thickness_m, "
            "conductivity_w_m_k, "
            "density_kg_m3, specific_heat_j_kg_k) in the scene's `thermal_materials` "
            "(docs/thermal.md)");
    node.check_keys(
        {"name", "description", "source", "model", "refractive_index", "parameters", "notes"});
    Material m;
    m.name = node.get_or<std::string>("name", fallback_name);
    if (m.name.empty()) node.fail("missing field `name`");
    m.source = node.get<std::string>("source");
    m.notes = node.get_or<std::string>("notes", "");
    if (const auto d = node.find("description"))
        m.notes = d->as<std::string>() + (m.notes.empty() ? "" : "\n" + m.notes);
    m.brdf = brdf_from_config(node);
    m.file = node.file();
    return m;
}

Material load_material(const std::filesystem::path& path) {
    return material_from_config(ConfigNode::load_file(path), path.stem().string());
}

MaterialLibrary MaterialLibrary::load_directory(const std::filesystem::path& directory) {
    if (!std::filesystem::is_directory(directory))
        fail("material library {}: not a directory", directory.string());
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(directory)) {
        const auto ext = entry.path().extension().string();
        if (entry.is_regular_file() && (ext == ".yaml" || ext == ".yml"))
            files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    MaterialLibrary library;
    for (const auto& file : files) {
        Material m = load_material(file);
        if (library.contains(m.name))
            fail("{}: material name \"{}\" is already used by {}", file.string(), m.name,
                 library.get(m.name).file.string());
        library.add(std::move(m));
    }
    return library;
}

void MaterialLibrary::add(Material material) {
    std::string name = material.name;
    m_materials.insert_or_assign(std::move(name), std::move(material));
}

const Material& MaterialLibrary::get(const std::string& name) const {
    const auto it = m_materials.find(name);
    if (it == m_materials.end()) {
        std::string known;
        for (const auto& [n, _] : m_materials) known += (known.empty() ? "" : ", ") + n;
        const std::string hint = closest_match(name, names());
        fail("unknown material \"{}\"{}; known materials: {}", name,
             hint.empty() ? "" : " (did you mean \"" + hint + "\"?)",
             known.empty() ? "(none)" : known);
    }
    return it->second;
}

std::vector<std::string> MaterialLibrary::names() const {
    std::vector<std::string> out;
    for (const auto& [n, _] : m_materials) out.push_back(n);
    return out;
}

}  // namespace tirpol::materials
