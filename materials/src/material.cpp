#include "tirpol/materials/material.h"

#include <algorithm>
#include <cmath>

#include "tirpol/core/config.h"
#include "tirpol/core/error.h"
#include "tirpol/materials/emissivity.h"
#include "tirpol/materials/lambertian.h"
#include "tirpol/materials/microfacet.h"
#include "tirpol/materials/smooth_fresnel.h"

namespace tirpol::materials {

namespace {

RefractiveIndexTable index_from_config(const ConfigNode& node) {
    node.check_keys({"n", "k", "file", "wavelength_um"});
    const std::string where = node.location() + " (" + node.path() + ")";
    if (node.has("file")) {
        if (node.has("n") || node.has("k") || node.has("wavelength_um"))
            node.fail("give either `file` or n/k values, not both");
        return RefractiveIndexTable::load(node.resolve_path(node.get<std::string>("file")));
    }
    if (node.has("wavelength_um")) {
        return RefractiveIndexTable(node.get<std::vector<double>>("wavelength_um"),
                                    node.get<std::vector<double>>("n"),
                                    node.get<std::vector<double>>("k"), where);
    }
    const double n = node.get_in_range("n", 1e-6, 1e6);
    const double k = node.get_in_range("k", 0.0, 1e6);
    return RefractiveIndexTable::constant({n, k}, where);
}

SpectralValue parameter(const ConfigNode& params, std::string_view key, double fallback, double lo,
                        double hi) {
    const auto node = params.find(key);
    return node ? SpectralValue::from_config(*node, lo, hi) : SpectralValue(fallback);
}

// Energy conservation over the model's data range: DHR ≤ 1 at normal, oblique and grazing angles.
void check_energy(const PolarizedBrdf& brdf, const ConfigNode& node) {
    auto [lo, hi] = brdf.valid_wavelength_range_um();
    std::vector<double> wavelengths;
    if (std::isfinite(hi)) {
        wavelengths = {lo, 0.5 * (lo + hi), hi};
    } else {
        wavelengths = {10.0};
    }
    EmissivityOptions coarse;
    coarse.radial_panels = 4;
    coarse.azimuth_panels = 4;
    for (double wl : wavelengths)
        for (double angle_deg : {0.0, 60.0, 85.0, 89.9}) {
            const double dhr = directional_hemispherical_reflectance(
                brdf, std::cos(deg_to_rad(angle_deg)), wl, coarse);
            if (dhr > 1.0 + 2e-3)
                node.fail(fmt::format(
                    "the parameters reflect more than they receive: directional-hemispherical "
                    "reflectance {:.4f} > 1 at {} µm, {}° (lower rho_d, rho_v or bias)",
                    dhr, wl, angle_deg));
        }
}

std::shared_ptr<const PolarizedBrdf> brdf_from_config(const ConfigNode& node) {
    const auto model = node.get<std::string>("model");
    const auto params = node.find("parameters");
    if (model == "smooth_fresnel") {
        if (params)
            params->fail("the smooth_fresnel model has no parameters besides refractive_index");
        return std::make_shared<SmoothFresnelBrdf>(index_from_config(node.at("refractive_index")));
    }
    if (model == "lambertian") {
        if (node.has("refractive_index"))
            node.at("refractive_index").fail("the lambertian model has no refractive index");
        if (!params) node.fail("missing field `parameters` (lambertian needs `reflectance`)");
        params->check_keys({"reflectance"});
        return std::make_shared<LambertianBrdf>(
            SpectralValue::from_config(params->at("reflectance"), 0.0, 1.0));
    }
    if (model == "microfacet") {
        if (!params) node.fail("missing field `parameters` (microfacet needs at least `sigma`)");
        params->check_keys({"sigma", "bias", "tau_deg", "omega_deg", "rho_d", "rho_v"});
        MicrofacetParameters p;
        p.index = index_from_config(node.at("refractive_index"));
        p.sigma = SpectralValue::from_config(params->at("sigma"), 1e-4, 10.0);
        p.bias = parameter(*params, "bias", 1.0, 0.0, 1.0);
        p.tau_deg = parameter(*params, "tau_deg", 90.0, 1e-3, 1e9);
        p.omega_deg = parameter(*params, "omega_deg", 1e6, 1e-3, 1e9);
        p.rho_d = parameter(*params, "rho_d", 0.0, 0.0, 1.0 / kPi);
        p.rho_v = parameter(*params, "rho_v", 0.0, 0.0, 1.0);
        auto brdf = std::make_shared<MicrofacetBrdf>(std::move(p));
        check_energy(*brdf, *params);
        return brdf;
    }
    node.at("model").fail("unknown model \"" + model +
                          "\" (expected smooth_fresnel, microfacet or lambertian)");
}

}  // namespace

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
