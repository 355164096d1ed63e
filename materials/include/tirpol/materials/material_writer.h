#pragma once
/// \file material_writer.h
/// Writes material files (docs/materials.md) so that the module that parses them (material.h) also
/// owns their text: what `tirpol fit` produces is loaded back by material_from_config unchanged.

#include <string>
#include <vector>

namespace tirpol::materials {

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

}  // namespace tirpol::materials
