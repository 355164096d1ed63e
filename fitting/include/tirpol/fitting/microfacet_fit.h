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
///
/// How a least-squares solve ended, as a type: Ceres' termination type (without Ceres in the
/// header) and its message. Written out as Ceres spells it ("CONVERGENCE: …") in the fit's JSON
/// and text report, so those files do not change.
///
/// Fixed-node quadrature of the polarized directional emissivity of the micro-facet model
/// (emissivity.h, paper eq 5 as Stokes):
///   ε_S0(θo) = 1 − ∫ M00(wi→wo) cosθi dωi,   ε_S1(θo) = −∫ M10(wi→wo) cosθi dωi,
/// with wo at polar angle θo and azimuth 0. The nodes depend only on θo (data), never on the
/// model's parameters, so the sum is a smooth function of the parameters that ceres::Jet
/// differentiates exactly (automatic differentiation "through the quadrature"). The materials
/// module's own integrator maps the BRDF's importance sampler onto the unit square, whose nodes
/// move with σ; this one is the Jet-friendly counterpart and is verified against it
/// (tests/fitting/emissivity_quadrature_test.cpp).
///
/// Nodes: composite Gauss–Legendre in θi ∈ [0, π/2] and φi ∈ [0, π] (M00 and M10 are even in φi by
/// the mirror symmetry of an isotropic surface, so the φi ∈ [π, 2π] half is the same and the
/// weights are doubled). Panel edges are graded towards the specular direction (θi = θo, φi = π),
/// where the micro-facet lobe concentrates, θo ± {0.04, 0.12, 0.3, 0.6} rad and π − {0.1, 0.3,
/// 0.7, 1.5} rad, and repeated scaled by 2·cosθo beyond 60°, where the lobe narrows in wi-space
/// like cosθo.
///
/// The 2σ interval of a fitted parameter as every output reports it (CLI text and JSON, Python's
/// FitResult.intervals_2sigma): value ± 2σ intersected with the parameter's bounds, since the fit
/// never leaves them and values beyond them (n < 1.0 for a bound of 1.0) are not possible results.
///
/// Measured polarized directional emissivity ε_S0(θ), ε_S1(θ) with standard (1σ) uncertainties: the
/// input of the fits (paper §3.2, Fig. 1), read from the emissivity CSV whose schema core owns
/// (tirpol/core/emissivity_csv.h; `tirpol extract-emissivity` writes it). The fit uses
/// view_angle_deg, eps_s0, eps_s0_std, eps_s1, eps_s1_std and, when present, name and
/// wavelength_um. ε_S1 is in the s/p frame of the plane of emission (pbrdf.h): S1 < 0 means
/// polarized in the plane of emission. Rows in the `image` frame are taken as that frame, which
/// they equal when the plane of emission is vertical in the image (a horizontal panel viewed
/// obliquely, docs/fitting.md).

#include <fmt/format.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "tirpol/core/geometry.h"
#include "tirpol/materials/fresnel.h"
#include "tirpol/materials/microfacet.h"

namespace tirpol::fitting {

/// One measured view angle.
struct EmissivitySample {
    double angle_deg = 0.0;   ///< emission (view) angle from the surface normal, [0°, 90°]
    double eps_s0 = 0.0;      ///< ε_S0 = 1 − DHR
    double eps_s0_std = 0.0;  ///< standard (1σ) uncertainty of eps_s0, > 0
    double eps_s1 =
        0.0;  ///< ε_S1 (plane-of-emission frame, < 0 for emission polarized in that plane)
    double eps_s1_std = 0.0;  ///< standard (1σ) uncertainty of eps_s1, > 0
    std::string name;         ///< target/ROI name from the CSV (may be empty)
};

/// Samples measured in one band (effective wavelength) from one source.
struct EmissivityDataset {
    std::string
        source;  ///< file (or description) the samples came from, for messages and provenance
    double wavelength_um = 10.0;  ///< effective wavelength at which the model's n + ik is evaluated
    std::vector<EmissivitySample> samples;
};

/// Reads an emissivity CSV (file comment). Rows with a `wavelength_um` column value go to one
/// dataset per distinct wavelength; without that column every row goes to one dataset at
/// `default_wavelength_um`. Lines starting with '#' and blank lines are skipped. Throws
/// tirpol::Error naming file, line and column for a missing column, a non-number, and every check
/// of `validate_dataset`.
std::vector<EmissivityDataset> load_emissivity_csv(const std::filesystem::path& path,
                                                   double default_wavelength_um = 10.0);

/// Checks one dataset: at least one sample; finite values; angles in [0°, 90°]; eps_s0 in [0, 1]
/// and eps_s1 in [-1, 1] within limits::kEmissivityTolerance (measurement noise); uncertainties
/// finite and > 0; wavelength finite and > 0. Throws tirpol::Error naming `dataset.source` and the
/// sample.
void validate_dataset(const EmissivityDataset& dataset);

/// Writes samples as an emissivity CSV (core/emissivity_csv.h) in the plane-of-emission frame, with
/// their wavelength_um and unknown columns empty, so that load_emissivity_csv reads them back
/// exactly.
std::string emissivity_csv(const std::vector<EmissivityDataset>& datasets);

struct QuadratureOptions {
    int order =
        4;  ///< Gauss–Legendre nodes per panel (1..16); 4 keeps |Δε| < 1e-3 for σ ≥ 0.1 (test)
};

/// The quadrature nodes of one emission angle, with the parameter-independent geometry cached.
class EmissivityQuadrature {
public:
    EmissivityQuadrature(double emission_angle_rad, const QuadratureOptions& options = {});

    /// (ε_S0, ε_S1) of the micro-facet model with parameters `p` (τ, Ω in radians) at this angle.
    ///
    /// Column 0 of shell_target_mueller (materials/shell_target_math.h) summed over the nodes with
    /// that header's building blocks (gaussian_slope_falloff, smith_lambda,
    /// beard_maxwell_shadowing_reciprocal, fresnel_reflectances), arranged for speed (this runs
    /// with ceres::Jet in every residual evaluation): e0 is unpolarized, so only M00 = s·(Rs+Rp)/2
    /// + ρ_D + 2ρ_V/(cosθi+cosθo) and M10 = s·(Rs−Rp)/2·cos2αo are needed (the frame rotations only
    /// mix columns 1 and 2, and the Fresnel matrix has m20 = 0), with s = bias·D·G·SO/(4 cosθi
    /// cosθo). ñ², 1/(2σ²), 1/τ, 1/Ω, D's constant 1/(2πσ²) and Smith's Λ(θo) are computed once per
    /// call, Λ(θi) once per θi row; D's 1/cos⁴θN is in the node weight. The diffuse and volume
    /// terms are linear in ρ_D, ρ_V, with node sums precomputed. The test checks this against the
    /// materials module's integrator, which evaluates shell_target_mueller itself.
    template <typename T>
    std::pair<T, T> emissivity(const materials::ShellTargetParameters<T>& p) const {
        const T s2 = p.sigma * p.sigma;
        const T inv_2s2 = T(1.0) / (T(2.0) * s2);
        const T d_norm =
            p.bias / (T(2.0 * kPi) * s2);  // bias / (2πσ²), the constant of D times bias
        const T lambda_o = materials::smith_lambda(p.sigma, m_cot_o);
        const materials::TinyComplex<T> eps{p.n * p.n - p.k * p.k, T(2.0) * p.n * p.k};  // ñ²
        const T inv_tau = T(1.0) / p.tau_rad, inv_omega = T(1.0) / p.omega_rad;

        T specular_s0(0.0), specular_s1(0.0);
        for (const Row& row : m_rows) {
            const T shadow =
                T(1.0) / (T(1.0) + materials::smith_lambda(p.sigma, row.cot_i) + lambda_o);
            T row_s0(0.0), row_s1(0.0);
            for (auto it = m_nodes.begin() + static_cast<std::ptrdiff_t>(row.begin),
                      end = m_nodes.begin() + static_cast<std::ptrdiff_t>(row.end);
                 it != end; ++it) {
                const Node& nd = *it;
                const T d = materials::gaussian_slope_falloff(inv_2s2, nd.tan2_n);
                const T so = materials::beard_maxwell_shadowing_reciprocal(inv_tau, inv_omega,
                                                                           nd.theta_n, nd.beta);
                const materials::FresnelReflectances<T> r =
                    materials::fresnel_reflectances(eps, nd.cos_beta);
                const T w = d * so * T(nd.weight_over_c4);
                row_s0 += w * (r.rs2 + r.rp2);
                row_s1 += w * (r.rs2 - r.rp2) * T(nd.cos_2alpha_o);
            }
            specular_s0 += shadow * row_s0;
            specular_s1 += shadow * row_s1;
        }
        // The ½ of (Rs ± Rp)/2 is folded in here.
        const T reflected_s0 =
            T(0.5) * d_norm * specular_s0 + p.rho_d * T(m_diffuse_sum) + p.rho_v * T(m_volume_sum);
        const T reflected_s1 = T(0.5) * d_norm * specular_s1;
        return {T(1.0) - reflected_s0, -reflected_s1};
    }

    double emission_angle_rad() const { return m_emission_angle_rad; }
    std::size_t node_count() const { return m_nodes.size(); }

private:
    struct Node {
        double tan2_n, theta_n;  ///< facet tilt
        double cos_beta, beta;   ///< incidence on the facet
        double cos_2alpha_o;     ///< facet → macro frame of the exitant beam
        double weight_over_c4;  ///< quadrature weight × cosθi sinθi × 2 / (4 cosθi cosθo cos⁴θN)
    };
    struct Row {
        double cot_i;            ///< cotangent of this row's θi (Smith's Λ)
        std::size_t begin, end;  ///< its nodes in m_nodes
    };
    double m_emission_angle_rad;
    double m_cot_o = 0.0;
    double m_diffuse_sum = 0.0;  ///< Σ weight·cosθi: ∫ cosθi dωi (= π up to quadrature error)
    double m_volume_sum = 0.0;  ///< Σ weight·2/(cosθi + cosθo)
    std::vector<Node> m_nodes;
    std::vector<Row> m_rows;
};

struct SolverTermination {
    /// ceres::TerminationType, plus NotRun for a result no solve has filled in yet.
    enum class Type { NotRun, Convergence, NoConvergence, Failure, UserSuccess, UserFailure };
    Type type = Type::NotRun;
    std::string message;  ///< ceres::Solver::Summary::message

    /// "TYPE: message" (Ceres' TerminationTypeToString spelling); empty for NotRun.
    std::string text() const;
};

/// "NOT_RUN", "CONVERGENCE", "NO_CONVERGENCE", "FAILURE", "USER_SUCCESS", "USER_FAILURE".
std::string_view to_string(SolverTermination::Type type);

/// Writes text() (for test failure messages).
std::ostream& operator<<(std::ostream& out, const SolverTermination& termination);

}  // namespace tirpol::fitting

/// Formats as text(), so messages keep reading "CONVERGENCE: …".
template <>
struct fmt::formatter<tirpol::fitting::SolverTermination> : fmt::formatter<std::string> {
    template <typename FormatContext>
    auto format(const tirpol::fitting::SolverTermination& t, FormatContext& ctx) const {
        return fmt::formatter<std::string>::format(t.text(), ctx);
    }
};

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

/// A closed interval [lower, upper] of a parameter's value.
struct ParameterInterval {
    double lower = 0.0;
    double upper = 0.0;
    bool clipped = false;  ///< value ± 2σ reached past a bound and was cut there
};

/// value ± 2σ of `p` clipped to [p.lower, p.upper]; for a fixed parameter, [value, value].
inline ParameterInterval interval_2sigma(const FittedParameter& p) {
    if (p.fixed) return {p.value, p.value, false};
    const double lo = p.value - 2.0 * p.std_uncertainty, hi = p.value + 2.0 * p.std_uncertainty;
    return {std::max(p.lower, lo), std::min(p.upper, hi), lo < p.lower || hi > p.upper};
}

}  // namespace tirpol::fitting
