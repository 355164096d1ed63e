#pragma once
/// \file python_config.h
/// Python dicts as tirpol configs: the dict is written as JSON (a subset of YAML) and parsed by
/// core's ConfigNode, so a scene or camera given as a dict goes through the same loader, checks and
/// error messages as a YAML file — no second parser.

#include <pybind11/pybind11.h>

#include <filesystem>
#include <string>

#include "tirpol/core/config.h"

namespace tirpol::python {

/// `config` (dict, list, numbers, strings) as a ConfigNode. Messages name `source_name` as the
/// file; relative paths inside resolve against its directory.
ConfigNode config_from_python(const pybind11::handle& config,
                              const std::filesystem::path& source_name);

}  // namespace tirpol::python
