// `model: lambertian`: an unpolarized diffuse reflector with a spectral `reflectance`.

#include "lambertian.h"

#include "model_config.h"

namespace tirpol::materials::models {

std::shared_ptr<const PolarizedBrdf> lambertian_from_config(const ConfigNode& material) {
    if (material.has("refractive_index"))
        material.at("refractive_index").fail("the lambertian model has no refractive index");
    const auto params = material.find("parameters");
    if (!params) material.fail("missing field `parameters` (lambertian needs `reflectance`)");
    params->check_keys({"reflectance"});
    return std::make_shared<LambertianBrdf>(
        SpectralValue::from_config(params->at("reflectance"), 0.0, 1.0));
}

}  // namespace tirpol::materials::models
