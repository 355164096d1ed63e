#pragma once
/// \file material.h
/// Materials as people write them: YAML files (docs/materials.md) naming a pBRDF model, its
/// parameters, and the literature source of the values; and a library of them (config/materials/).
///
/// ```yaml
/// name: flat_black_paint
/// source: "where the numbers come from"
/// model: microfacet              # smooth_fresnel | microfacet | lambertian
/// refractive_index: {n: 1.6, k: 0.1}     # or {file: data/x.yml} (refractiveindex.info / CSV)
/// parameters: {sigma: 0.3, bias: 1, tau_deg: 15, omega_deg: 60, rho_d: 0.005, rho_v: 0}
/// notes: "free text"
/// ```
///
/// A material named on a command line the way scenes name them: a file or a library name.
///
/// Writes material files (docs/materials.md) so that the module that parses them (material.h) also
/// owns their text: what `tirpol fit` produces is loaded back by material_from_config unchanged.
///
/// The Mueller BRDF of a material for one incident/exitant pair of directions, as `tirpol brdf`
/// reports it: the evaluation and its two formats (JSON, text).

#include <array>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tirpol/core/stokes.h"
#include "tirpol/materials/pbrdf.h"

namespace tirpol {
class ConfigNode;
}

namespace tirpol::materials {

struct Material {
    std::string name;
    std::string source;  ///< literature source(s) of the values, as written in the file
    std::string notes;   ///< free text (ranges, caveats)
    std::shared_ptr<const PolarizedBrdf> brdf;
    std::filesystem::path file;  ///< where it was loaded from (empty for inline definitions)
};

/// Builds a material from a parsed YAML mapping (a file's root or a scene's inline `material:`).
/// Relative data paths resolve against the node's file. Unknown keys are errors
/// (ConfigNode::check_keys); every error names file:line and the field. `fallback_name` is used
/// when the node has no `name`.
Material material_from_config(const ConfigNode& node, const std::string& fallback_name = "");

/// Loads one material file.
Material load_material(const std::filesystem::path& path);

/// All materials of a directory (its *.yaml / *.yml files, not recursive), by name.
class MaterialLibrary {
public:
    /// Loads every material file of `directory`; error if two share a name, or the directory is
    /// missing.
    static MaterialLibrary load_directory(const std::filesystem::path& directory);

    /// Adds (or replaces) a material.
    void add(Material material);
    /// The material called `name`; error lists the known names.
    const Material& get(const std::string& name) const;
    bool contains(const std::string& name) const { return m_materials.count(name) != 0; }
    std::vector<std::string> names() const;

private:
    std::map<std::string, Material> m_materials;
};

/// The file a material argument names: a YAML file (any path with a '/' or ending in .yaml/.yml, or
/// an existing file), or else a library name resolved to config/materials/<name>.yaml
/// (find_config). Throws tirpol::Error naming a missing file, or an unknown name with the closest
/// library name and the list of names.
std::filesystem::path material_file(const std::string& name_or_path);

/// A micro-facet material as it is written: names as in the file, τ and Ω in degrees.
struct MicrofacetMaterialRecord {
    std::string name;
    std::string source;
    std::string notes;
    std::vector<std::string> comment_lines;  ///< provenance, written first as `# …` lines
    std::vector<double> wavelengths_um;  ///< one entry: a constant index {n, k}; several: a table
    std::vector<double> n;               ///< real index per wavelength
    std::vector<double> k;               ///< imaginary index per wavelength
    double sigma = 0.1;
    double bias = 1.0;
    double tau_deg = 90.0;
    double omega_deg = 1e6;
    double rho_d = 0.0;  ///< 1/sr
    double rho_v = 0.0;  ///< 1/sr
};

/// The material file text (`model: microfacet`). Numbers are written in shortest round-trip form,
/// so parsing gives the same doubles; strings are double-quoted (any text survives). Throws
/// tirpol::Error naming the material and field for an empty name, mismatched n/k/wavelength lists
/// or a non-finite value (the loader would refuse the file).
std::string microfacet_material_yaml(const MicrofacetMaterialRecord& material);

/// What to evaluate: a material (file or library name), a wavelength and two directions given as
/// zenith and azimuth in degrees.
struct BrdfEvaluationOptions {
    std::string material;  ///< YAML file or library name (material_file)
    double wavelength_um = 10.0;
    std::array<double, 2> incident_deg{};  ///< zenith [0, 90], azimuth
    std::array<double, 2> exitant_deg{};   ///< zenith [0, 90], azimuth
};

/// The result of evaluate_brdf.
struct BrdfEvaluation {
    std::string material;  ///< the material's name
    std::string model;     ///< its pBRDF model
    double wavelength_um = 0.0;
    std::array<double, 2> incident_deg{}, exitant_deg{};
    MuellerMatrix mueller_brdf_per_sr = MuellerMatrix::Zero();
    std::vector<BrdfParameter> parameters;  ///< at the wavelength
    bool has_delta = false;                 ///< a specular delta lobe outside the finite BRDF
};

/// The unit direction of zenith `theta_deg` and azimuth `phi_deg` in the surface frame (normal +z).
/// Throws tirpol::Error when the zenith is outside [0, 90] or the azimuth is not finite.
Vec3 direction_from_zenith_azimuth_deg(double theta_deg, double phi_deg);

/// Loads the material and evaluates its Mueller BRDF (incident Stokes in surface_frame(-wi, n),
/// exitant in surface_frame(wo, n)). Throws tirpol::Error for a bad direction, a material that
/// does not load, or a wavelength outside the material's data range.
BrdfEvaluation evaluate_brdf(const BrdfEvaluationOptions& options);

/// The JSON report (keys in docs/cli.md): material, model, wavelength_um, incident_deg,
/// exitant_deg, frames, mueller_brdf_per_sr (4 rows), parameters {name: {value, unit}}, has_delta.
nlohmann::json brdf_evaluation_json(const BrdfEvaluation& evaluation);

/// The text report: a heading, the 4×4 matrix, the delta-lobe note and the parameters.
std::string brdf_evaluation_text(const BrdfEvaluation& evaluation);

}  // namespace tirpol::materials
