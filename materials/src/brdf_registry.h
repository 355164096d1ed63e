#pragma once
// The pBRDF models by name (a material file's `model:`). Each model is one file
// src/models/<model>.cpp defining models::<model>_from_config; the build lists every file there
// (materials/CMakeLists.txt), so adding a model touches only its file and its test.

#include <memory>
#include <string>
#include <vector>

#include "tirpol/core/config.h"
#include "tirpol/materials/pbrdf.h"

namespace tirpol::materials {

/// Builds a model from its material node (`model`, `refractive_index`, `parameters`), failing at
/// the offending field when the node does not fit the model.
using BrdfFactory = std::shared_ptr<const PolarizedBrdf> (*)(const ConfigNode& material);

/// The registered model names, sorted.
std::vector<std::string> brdf_model_names();

/// The model named by the node's `model` field, built by its factory; an unknown name fails at
/// `model` listing the registered ones.
std::shared_ptr<const PolarizedBrdf> brdf_from_config(const ConfigNode& material);

}  // namespace tirpol::materials
