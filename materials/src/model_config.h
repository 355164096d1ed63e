#pragma once
// What the pBRDF models' factories (src/models/*.cpp) share when they read a material node: the
// refractive index, optional spectral parameters, and the energy check of a built model.

#include <string_view>

#include "tirpol/core/config.h"
#include "tirpol/materials/fresnel.h"
#include "tirpol/materials/microfacet.h"
#include "tirpol/materials/pbrdf.h"

namespace tirpol::materials {

/// `refractive_index`: either `file` (a CSV table) or n/k values, constant or per `wavelength_um`.
RefractiveIndexTable index_from_config(const ConfigNode& node);

/// The spectral parameter `key` of `params` within [lo, hi], or `fallback` when it is absent.
SpectralValue optional_parameter(const ConfigNode& params, std::string_view key, double fallback,
                                 double lo, double hi);

/// Energy conservation over the model's data range: fails at `node` when the directional-
/// hemispherical reflectance exceeds 1 at normal, oblique or grazing angles.
void check_energy(const PolarizedBrdf& brdf, const ConfigNode& node);

}  // namespace tirpol::materials
