#include "brdf_registry.h"

#include <algorithm>
#include <map>
#include <string_view>

namespace tirpol::materials {

namespace models {
#define TIRPOL_BRDF_MODEL(name) \
    std::shared_ptr<const PolarizedBrdf> name##_from_config(const ConfigNode& material);
#include "brdf_models.inc"
#undef TIRPOL_BRDF_MODEL
}  // namespace models

namespace {

// Built from the generated list of src/models/*.cpp: the factories are referenced here, so the
// linker keeps every model of the static library.
const std::map<std::string, BrdfFactory, std::less<>>& registry() {
    static const std::map<std::string, BrdfFactory, std::less<>> factories{
#define TIRPOL_BRDF_MODEL(name) {#name, &models::name##_from_config},
#include "brdf_models.inc"
#undef TIRPOL_BRDF_MODEL
    };
    return factories;
}

}  // namespace

std::vector<std::string> brdf_model_names() {
    std::vector<std::string> names;
    for (const auto& [name, _] : registry()) names.push_back(name);
    return names;
}

std::shared_ptr<const PolarizedBrdf> brdf_from_config(const ConfigNode& material) {
    const auto model = material.get<std::string>("model");
    const auto it = registry().find(model);
    if (it == registry().end()) {
        std::string known;
        for (const auto& name : brdf_model_names()) known += (known.empty() ? "" : ", ") + name;
        material.at("model").fail("unknown model \"" + model + "\" (expected one of: " + known +
                                  ")");
    }
    return it->second(material);
}

}  // namespace tirpol::materials
