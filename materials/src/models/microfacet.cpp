// `model: microfacet`: the paper's shell-target micro-facet pBRDF (σ, bias, τ, Ω, ρ_D, ρ_V) over a
// refractive index; checked for energy conservation when loaded.

#include "tirpol/materials/microfacet.h"

#include "model_config.h"
#include "tirpol/core/geometry.h"

namespace tirpol::materials::models {

std::shared_ptr<const PolarizedBrdf> microfacet_from_config(const ConfigNode& material) {
    const auto params = material.find("parameters");
    if (!params) material.fail("missing field `parameters` (microfacet needs at least `sigma`)");
    params->check_keys({"sigma", "bias", "tau_deg", "omega_deg", "rho_d", "rho_v"});
    MicrofacetParameters p;
    p.index = index_from_config(material.at("refractive_index"));
    p.sigma = SpectralValue::from_config(params->at("sigma"), 1e-4, 10.0);
    p.bias = optional_parameter(*params, "bias", 1.0, 0.0, 1.0);
    p.tau_deg = optional_parameter(*params, "tau_deg", 90.0, 1e-3, 1e9);
    p.omega_deg = optional_parameter(*params, "omega_deg", 1e6, 1e-3, 1e9);
    p.rho_d = optional_parameter(*params, "rho_d", 0.0, 0.0, 1.0 / kPi);
    p.rho_v = optional_parameter(*params, "rho_v", 0.0, 0.0, 1.0);
    auto brdf = std::make_shared<MicrofacetBrdf>(std::move(p));
    check_energy(*brdf, *params);
    return brdf;
}

}  // namespace tirpol::materials::models
