#include "model_config.h"

#include <cmath>
#include <string>
#include <vector>

#include "tirpol/core/error.h"
#include "tirpol/core/geometry.h"
#include "tirpol/materials/emissivity.h"

namespace tirpol::materials {

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

SpectralValue optional_parameter(const ConfigNode& params, std::string_view key, double fallback,
                                 double lo, double hi) {
    const auto node = params.find(key);
    return node ? SpectralValue::from_config(*node, lo, hi) : SpectralValue(fallback);
}

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

}  // namespace tirpol::materials
