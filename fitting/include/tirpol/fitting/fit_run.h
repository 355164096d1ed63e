#pragma once
/// \file fit_run.h
/// `tirpol fit` from files to files: the micro-facet model fitted to emissivity CSVs, written as a
/// material YAML (and a plot), and the report as JSON or text.
///
/// The micro-facet parameter settings as users write them (`tirpol fit --bound/--fix/--free`, the
/// Python module): NAME=LOWER:UPPER, NAME[=VALUE] and NAME, with NAME one of
/// microfacet_fit.h's parameter names (n, k, sigma, bias, tau_deg, omega_deg, rho_d, rho_v).
///
/// What a fit leaves behind: a material YAML in the materials module's format (material.h,
/// docs/materials.md) that `tirpol emissivity` and the renderer load directly, with the fit's
/// provenance in `source`/`notes` and in comments; a JSON report; a text summary for the terminal.
///
/// A plot like the paper's Fig. 1: measured ε_S0(θ) and ε_S1(θ) with 2σ error bars and the fitted
/// model curves, one panel each, one colour per dataset/band; axes, ticks, labels and a legend.
/// Drawn with OpenCV directly rather than core's write_line_plot, which has neither error bars nor
/// stacked panels; the tick positions are core's nice_ticks.

#include <array>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

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

/// The settings of every parameter, in fit order.
using ParameterSettings = std::array<ParameterSetting, kMicrofacetParameterCount>;

/// Applies "NAME=LOWER:UPPER" (e.g. sigma=0.05:0.8) to that parameter's bounds. Throws
/// tirpol::Error naming `item` for another shape, an unknown name or a bound that is not a finite
/// number.
void apply_parameter_bound(std::string_view item, ParameterSettings& settings);

/// Applies "NAME" (hold at its initial value) or "NAME=VALUE" (hold at VALUE). Throws
/// tirpol::Error naming `item` for an unknown name or a value that is not a finite number.
void apply_parameter_fix(std::string_view item, ParameterSettings& settings);

/// Applies "NAME": the parameter is fitted. Throws tirpol::Error for an unknown name.
void apply_parameter_free(std::string_view name, ParameterSettings& settings);

/// The data, the parameter settings as the command line writes them, the solver settings and the
/// files to write.
struct FitRunOptions {
    std::vector<std::string> data;    ///< emissivity CSVs
    std::vector<std::string> fix;     ///< NAME[=VALUE] (apply_parameter_fix)
    std::vector<std::string> free;    ///< NAME (apply_parameter_free)
    std::vector<std::string> bounds;  ///< NAME=LOWER:UPPER (apply_parameter_bound)
    std::string init;  ///< material whose micro-facet parameters are the first start, or ""
    int starts = 16;
    std::uint64_t seed = 1;
    int quadrature_order = 4;
    double wavelength_um = 10.0;  ///< of data without a wavelength_um column
    bool scale_covariance = false;
    std::string output;  ///< material YAML
    std::string plot;    ///< PNG, or ""
    std::string name;    ///< material name; "" = the output file's stem
    bool force = false;  ///< existing outputs may be replaced (OutputGuard)
};

/// What run_fit fitted and wrote.
struct FitRun {
    MicrofacetFitResult result;
    std::vector<EmissivityDataset> datasets;  ///< as fitted
    FitProvenance provenance;
    std::string output, plot;
};

/// Applies --bound, --free and --fix to `settings`; throws OptionValueError naming the option of
/// the first item that does not parse or names no parameter.
void apply_parameter_options(const FitRunOptions& options, ParameterSettings& settings);

/// Checks the outputs against the inputs (OutputGuard: OutputConflict before any work), loads the
/// data, fits, writes the material YAML (with provenance) and the plot. Throws
/// OptionValueError for a bad parameter option, tirpol::Error for data or an --init material that
/// does not read (or is not micro-facet). A fit that ends unusable is returned, not thrown.
FitRun run_fit(const FitRunOptions& options);

/// fit_report_json with material_file and plot_file.
nlohmann::json fit_run_json(const FitRun& run);

/// fit_report_text and the files written.
std::string fit_run_text(const FitRun& run);

}  // namespace tirpol::fitting
