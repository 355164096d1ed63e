#pragma once
/// \file microfacet_fit.h
/// Weighted nonlinear least-squares fit of the micro-facet pBRDF (materials/shell_target_math.h: n,
/// k, σ, bias, τ, Ω, ρ_D, ρ_V) to measured polarized emissivity ε_S0(θ), ε_S1(θ) (paper §3.2, Fig.
/// 1), with Ceres Solver:
///   minimise ½ Σ_samples [ ((ε_S0,model − ε_S0)/σ_S0)² + ((ε_S1,model − ε_S1)/σ_S1)² ]
/// over the free parameters, each inside its bounds, the others held fixed. Derivatives by
/// automatic differentiation (ceres::Jet) through the fixed-node quadrature
/// (emissivity_quadrature.h), or central differences for comparison. Several starts (the user's
/// initial values, then a Latin hypercube in the bounds from a fixed seed) guard against local
/// minima; the best is kept.
///
/// Joint fits: several datasets (view-angle series or wavelength bands) of the same material share
/// σ, bias, τ, Ω, ρ_D, ρ_V; the complex index n + ik is fitted per distinct wavelength.
///
/// Uncertainties: covariance (JᵀJ)⁻¹ at the minimum (ceres::Covariance), optionally multiplied by
/// χ²/dof when the measurement uncertainties are not trusted (Press et al., Numerical Recipes 3rd
/// ed., §15.4 and §15.6; the "s²" scaling of Bevington & Robinson §8.5).

#include <Eigen/Core>
#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tirpol/core/geometry.h"
#include "tirpol/fitting/emissivity_data.h"
#include "tirpol/fitting/emissivity_quadrature.h"
#include "tirpol/fitting/solver_termination.h"
#include "tirpol/materials/shell_target_math.h"

namespace tirpol::fitting {

/// The micro-facet model's parameters in fit order, with the units of the material file
/// (material.h): τ and Ω in degrees.
enum class MicrofacetParameter : std::size_t {
    n,
    k,
    sigma,
    bias,
    tau_deg,
    omega_deg,
    rho_d,
    rho_v
};
inline constexpr std::size_t kMicrofacetParameterCount = 8;

/// "n", "k", "sigma", "bias", "tau_deg", "omega_deg", "rho_d", "rho_v".
std::string_view parameter_name(MicrofacetParameter p);
/// The parameter called `name`; throws tirpol::Error listing the valid names otherwise.
MicrofacetParameter parameter_from_name(std::string_view name);

/// Values in MicrofacetParameter order (τ, Ω in degrees, as the fit holds them) → the model's
/// parameters (τ, Ω in radians); templated for the residual's Jets. The one place the two orders
/// meet.
template <typename T>
materials::ShellTargetParameters<T> model_parameters_from_fit_order(
    const std::array<T, kMicrofacetParameterCount>& v) {
    const T per_degree(deg_to_rad(1.0));
    return {v[0], v[1], v[2], v[3], v[4] * per_degree, v[5] * per_degree, v[6], v[7]};
}

/// The inverse: the model's parameters as values in MicrofacetParameter order (τ, Ω in degrees).
std::array<double, kMicrofacetParameterCount> fit_order_values(
    const materials::ShellTargetParameters<double>& p);

/// Starting value, bounds and whether the parameter is held fixed (at `initial`).
struct ParameterSetting {
    double initial = 0.0;
    double lower = 0.0;
    double upper = 0.0;
    bool fixed = false;
};

/// Defaults: n 1.5 ∈ [1.05, 4], k 0.1 ∈ [0, 2], σ 0.2 ∈ [0.05, 1], ρ_D 0.01 ∈ [0, 1/π] free;
/// bias 1 ∈ [0, 1], τ 90° ∈ [1°, 180°], Ω 10⁶° ∈ [1°, 10⁶°] (no Beard–Maxwell shadowing), ρ_V 0 ∈
/// [0, 1] fixed (materials' defaults; emissivity curves rarely constrain them, docs/fitting.md).
std::array<ParameterSetting, kMicrofacetParameterCount> default_parameter_settings();

enum class Derivatives {
    Automatic,  ///< ceres::DynamicAutoDiffCostFunction (Jets through the quadrature, free
                ///< parameters only)
    Numeric,    ///< ceres::NumericDiffCostFunction, central differences (reference for benchmarks)
};

struct MicrofacetFitOptions {
    std::array<ParameterSetting, kMicrofacetParameterCount> parameters =
        default_parameter_settings();
    int starts = 16;         ///< number of starts (≥ 1); the first is `initial`
    std::uint64_t seed = 1;  ///< Latin-hypercube seed (deterministic)
    QuadratureOptions quadrature;
    Derivatives derivatives = Derivatives::Automatic;
    int max_iterations = 200;  ///< per start
    /// Multiply the covariance by χ²/dof (use when the stated uncertainties are not trusted).
    bool scale_covariance_by_reduced_chi2 = false;
    double correlation_warning = 0.95;  ///< warn about parameter pairs with |ρ| above this
    int threads = 1;                    ///< Ceres threads per start
    /// Checked after every Ceres iteration (an IterationCallback returning SOLVER_ABORT) and before
    /// each start: once set, solve() throws tirpol::Cancelled (how the Python module stops a fit on
    /// Ctrl-C). Null: never.
    const std::atomic<bool>* cancel = nullptr;
};

/// One fitted parameter (a free or fixed value of the model).
struct FittedParameter {
    std::string name;  ///< "n", or "n@8.5um" for a per-band index in a multi-band fit
    MicrofacetParameter kind = MicrofacetParameter::n;
    std::optional<double> wavelength_um;  ///< band of a per-band n or k
    double value = 0.0;
    bool fixed = false;
    double std_uncertainty = 0.0;  ///< standard uncertainty (0 when fixed or unavailable)
    double lower = 0.0, upper = 0.0;
    bool at_bound = false;  ///< within 1e-6·(upper − lower) of a bound
};

/// Model and whitened residuals of one measured sample at the best fit.
struct SampleFit {
    std::size_t dataset = 0, sample = 0;
    double angle_deg = 0.0;
    double model_s0 = 0.0, model_s1 = 0.0;
    double residual_s0 = 0.0, residual_s1 = 0.0;  ///< (model − measured)/σ
};

/// What one start did.
struct StartOutcome {
    std::vector<double> initial;  ///< all parameter values at the start (parameter_names order)
    double chi2 = 0.0;            ///< final χ² = 2 × Ceres cost
    bool usable = false;          ///< ceres::Solver::Summary::IsSolutionUsable
    SolverTermination termination;
    int iterations = 0;
    bool reached_best = false;  ///< χ² within 1e-6 (relative) + 1e-9 of the best start's
};

struct MicrofacetFitResult {
    std::vector<double> wavelengths_um;       ///< distinct wavelengths (bands), ascending
    std::vector<FittedParameter> parameters;  ///< all values, parameter_names order
    std::vector<std::size_t> free_indices;    ///< indices into `parameters` of the free ones
    Eigen::MatrixXd covariance;               ///< of the free parameters (free_indices order)
    Eigen::MatrixXd correlation;
    bool covariance_available = false;
    bool covariance_scaled = false;  ///< multiplied by χ²/dof
    double chi2 = 0.0;
    int dof = 0;  ///< residuals − free parameters
    double reduced_chi2 = 0.0;
    std::vector<SampleFit> samples;
    SolverTermination termination;  ///< the best start's
    bool usable = false;
    std::string solver_report;  ///< ceres::Solver::Summary::BriefReport of the best start
    std::vector<StartOutcome> starts;
    double fraction_reaching_best = 0.0;  ///< of the starts
    std::vector<std::string> warnings;    ///< degenerate pairs, bounds, convergence, χ²/dof
    long residual_evaluations = 0;        ///< over all starts
    long jacobian_evaluations = 0;

    /// The parameter of the given kind (for n, k: at band `band`).
    const FittedParameter& get(MicrofacetParameter p, std::size_t band = 0) const;
    /// All model parameters for band `band` in the templated form (τ, Ω in radians).
    materials::ShellTargetParameters<double> model_parameters(std::size_t band = 0) const;
};

/// Result of ceres::GradientChecker over every residual block.
struct GradientCheckReport {
    bool ok = true;  ///< every block within the relative precision
    double worst_relative_error =
        0.0;                  ///< max over blocks of GradientChecker's maximum relative error
    std::string first_error;  ///< GradientChecker's message for the first failing block
};

/// A fit problem: validated data, options, the Ceres residual blocks.
class MicrofacetFitProblem {
public:
    /// Validates (validate_dataset; settings: lower ≤ initial ≤ upper, finite, lower < upper for
    /// free ones; enough residuals: 2 per sample, more than the free parameters). Throws
    /// tirpol::Error.
    MicrofacetFitProblem(std::vector<EmissivityDataset> datasets, MicrofacetFitOptions options);
    ~MicrofacetFitProblem();
    MicrofacetFitProblem(MicrofacetFitProblem&&) noexcept;
    MicrofacetFitProblem& operator=(MicrofacetFitProblem&&) noexcept;

    /// Multi-start fit, covariance and report.
    MicrofacetFitResult solve() const;

    /// Names of all parameter values (per-band n, k first, then the shared ones).
    std::vector<std::string> parameter_names() const;
    /// Their starting values (the settings' `initial`).
    std::vector<double> initial_values() const;
    std::size_t residual_count() const;
    std::size_t free_parameter_count() const;
    const std::vector<EmissivityDataset>& datasets() const;
    const std::vector<double>& wavelengths_um() const;

    /// Whitened residuals at `values` (parameter_names order) and, when `jacobian` is given, their
    /// derivatives (row-major, residual_count × values.size(); zero columns for fixed parameters).
    void evaluate(const std::vector<double>& values, std::vector<double>* residuals,
                  std::vector<double>* jacobian = nullptr) const;

    /// ceres::GradientChecker on every residual block at `values`: the automatic derivatives
    /// against central differences.
    GradientCheckReport check_gradients(const std::vector<double>& values,
                                        double relative_precision = 1e-6) const;

private:
    struct Impl;
    std::unique_ptr<Impl> m;
};

}  // namespace tirpol::fitting
