#pragma once
// The sky types by name (a scene's `sky: {type: …}`). Each type is one file
// src/skies/<type>.cpp defining its SkyModel and skies::<type>_from_config; the build lists every
// file there (simulation/CMakeLists.txt), so adding a sky type touches only its file and its test.

#include <optional>
#include <string>
#include <vector>

#include "tirpol/core/config.h"
#include "tirpol/core/radiometry.h"
#include "tirpol/simulation/scene.h"

namespace tirpol::simulation {

/// A sky as a grey body: emissivity ε(θ) and temperature T(θ) of the zenith angle θ; below the
/// horizon (cos θ ≤ 0) each model gives its horizon value.
class SkyModel {
public:
    virtual ~SkyModel() = default;
    /// Effective emissivity at the zenith angle θ given by cos θ.
    virtual double emissivity(double cos_zenith) const = 0;
    /// Temperature, K, at the zenith angle θ given by cos θ.
    virtual double temperature_k(double cos_zenith) const = 0;
    /// The temperature when it does not depend on the direction: then Planck's law is evaluated
    /// once per wavelength (Sky::AtWavelength). Empty: evaluated per direction.
    virtual std::optional<double> uniform_temperature_k() const { return std::nullopt; }
    /// emissivity(cos_zenith) to rounding, in the form the renderer evaluates at every path end;
    /// a model overrides it where a cheaper form exists.
    virtual double emissivity_per_path(double cos_zenith) const { return emissivity(cos_zenith); }
};

/// Builds a sky from its `sky:` node (`type` and the type's fields), failing at the offending
/// field; `band` converts band radiances to brightness temperatures.
using SkyFactory = Sky (*)(const ConfigNode& node, const Band& band);

/// The registered sky type names, sorted.
std::vector<std::string> sky_type_names();

}  // namespace tirpol::simulation
