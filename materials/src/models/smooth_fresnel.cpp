// `model: smooth_fresnel`: a specular interface with the Fresnel Mueller matrix; only a refractive
// index.

#include "smooth_fresnel.h"

#include "model_config.h"

namespace tirpol::materials::models {

std::shared_ptr<const PolarizedBrdf> smooth_fresnel_from_config(const ConfigNode& material) {
    if (const auto params = material.find("parameters"))
        params->fail("the smooth_fresnel model has no parameters besides refractive_index");
    return std::make_shared<SmoothFresnelBrdf>(index_from_config(material.at("refractive_index")));
}

}  // namespace tirpol::materials::models
