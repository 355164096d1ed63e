#pragma once
/// \file fit_output.h
/// What a fit leaves behind: a material YAML in the materials module's format (material.h,
/// docs/materials.md) that `tirpol emissivity` and the renderer load directly, with the fit's
/// provenance in `source`/`notes` and in comments; a JSON report; a text summary for the terminal.
///
/// A plot like the paper's Fig. 1: measured ε_S0(θ) and ε_S1(θ) with 2σ error bars and the fitted
/// model curves, one panel each, one colour per dataset/band; axes, ticks, labels and a legend.
/// Drawn with OpenCV directly rather than core's write_line_plot, which has neither error bars nor
/// stacked panels; the tick positions are core's nice_ticks.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tirpol/fitting/emissivity_data.h"
#include "tirpol/fitting/microfacet_fit.h"

namespace tirpol::fitting {

struct FitProvenance {
    std::vector<std::string> data_files;  ///< the measured CSVs
    std::string date_utc;                 ///< ISO 8601, e.g. 2026-11-22T17:03:00Z
    std::string command;                  ///< how the fit was run (for the record)
};

/// Material YAML for the fitted micro-facet model: `refractive_index` {n, k} for one band, or
/// {wavelength_um, n, k} lists for a multi-band fit; `parameters` σ, bias, τ°, Ω°, ρ_D, ρ_V;
/// `source` naming data, date, χ²/dof and the termination; `notes` with every parameter ± 2σ, the
/// fixed ones and the warnings; a comment block with the correlation matrix and per-angle
/// residuals.
std::string fitted_material_yaml(const std::string& name, const MicrofacetFitResult& result,
                                 const FitProvenance& provenance);

/// Machine-readable report (keys in docs/fitting.md).
nlohmann::json fit_report_json(const MicrofacetFitResult& result,
                               const std::vector<EmissivityDataset>& datasets,
                               const FitProvenance& provenance);

/// Human-readable summary: termination, χ²/dof, parameters ± 2σ, correlations, residuals per angle,
/// warnings.
std::string fit_report_text(const MicrofacetFitResult& result,
                            const std::vector<EmissivityDataset>& datasets);

/// Writes the PNG (atomically). The curves are the fit's own quadrature at 0.5° steps.
void write_fit_plot(const std::filesystem::path& png,
                    const std::vector<EmissivityDataset>& datasets,
                    const MicrofacetFitResult& result, const std::string& title,
                    const QuadratureOptions& quadrature = {});

}  // namespace tirpol::fitting
