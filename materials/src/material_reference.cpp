#include <algorithm>
#include <vector>

#include "tirpol/core/config.h"
#include "tirpol/core/error.h"
#include "tirpol/core/source_tree.h"
#include "tirpol/materials/material.h"

namespace tirpol::materials {

std::filesystem::path material_file(const std::string& name_or_path) {
    const bool path_like = name_or_path.find('/') != std::string::npos ||
                           name_or_path.ends_with(".yaml") || name_or_path.ends_with(".yml");
    if (path_like || std::filesystem::is_regular_file(name_or_path)) {
        if (!std::filesystem::is_regular_file(name_or_path))
            fail("material file {}: no such file", name_or_path);
        return name_or_path;
    }
    const std::filesystem::path dir = find_config("materials");
    for (const char* ext : {".yaml", ".yml"})
        if (const auto p = dir / (name_or_path + ext); std::filesystem::is_regular_file(p))
            return p;
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        const auto ext = entry.path().extension().string();
        if (entry.is_regular_file() && (ext == ".yaml" || ext == ".yml"))
            names.push_back(entry.path().stem().string());
    }
    std::sort(names.begin(), names.end());
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    const std::string hint = closest_match(name_or_path, names);
    fail("material '{}': neither a file nor a library material{}; library ({}): {}", name_or_path,
         hint.empty() ? "" : " — did you mean '" + hint + "'?", dir.string(), list);
}

}  // namespace tirpol::materials
