#include <map>
#include <string_view>

#include "sky_model.h"

namespace tirpol::simulation {

namespace skies {
#define TIRPOL_SKY_TYPE(name) Sky name##_from_config(const ConfigNode& node, const Band& band);
#include "sky_types.inc"
#undef TIRPOL_SKY_TYPE
}  // namespace skies

namespace {

// Built from the generated list of src/skies/*.cpp: the factories are referenced here, so the
// linker keeps every sky type of the static library.
const std::map<std::string, SkyFactory, std::less<>>& registry() {
    static const std::map<std::string, SkyFactory, std::less<>> factories{
#define TIRPOL_SKY_TYPE(name) {#name, &skies::name##_from_config},
#include "sky_types.inc"
#undef TIRPOL_SKY_TYPE
    };
    return factories;
}

}  // namespace

std::vector<std::string> sky_type_names() {
    std::vector<std::string> names;
    for (const auto& [name, _] : registry()) names.push_back(name);
    return names;
}

Sky Sky::from_config(const ConfigNode& node, const Band& band) {
    const auto type = node.get<std::string>("type");
    const auto it = registry().find(type);
    if (it == registry().end()) {
        std::string known;
        for (const auto& name : sky_type_names()) known += (known.empty() ? "" : ", ") + name;
        node.at("type").fail("unknown sky type \"" + type + "\" (expected one of: " + known + ")");
    }
    return it->second(node, band);
}

}  // namespace tirpol::simulation
