#pragma once
/// \file noisy_model_fit.h
/// Weighted least squares of a model whose predictions carry their own noise — a Monte Carlo render
/// evaluated with common random numbers (the same seed every evaluation): each evaluation returns
/// values and their variances, and
///   minimise ½ Σ_j (measured_j − model_j(θ))² / (σ_meas,j² + σ_model,j²)
/// with Ceres (Levenberg–Marquardt, bounds on every parameter). Derivatives by finite differences
/// (central or forward), since the model is a black box of a few parameters. The weights are held
/// fixed during a solve (a noisy variance estimate that moved with θ would put its noise into the
/// derivatives): taken at the start, then, when `reweight` is set, once more at the first solution
/// and solved again from there (iteratively reweighted least squares, one step).
///
/// With common random numbers the model's Monte Carlo error is (nearly) the same offset at every θ
/// near the solution, so it acts as a second measurement error: the covariance (JᵀWJ)⁻¹ from
/// ceres::Covariance, with W = 1/(σ_meas² + σ_model²), includes it (Press et al., Numerical Recipes
/// 3rd ed., §15.4–15.5).
///
/// "Nearly": the error e(θ) moves with θ, and its spread with it. Averaged over the model's random
/// numbers the objective is Σ w_j [(measured_j − E model_j(θ))² + Var model_j(θ)] (+ the
/// measurement's variance, which does not depend on θ), so its minimum is pulled towards parameters
/// whose renders are less noisy, by δθ = −½ (JᵀWJ)⁻¹ ∇_θ Σ w_j Var model_j(θ). The fit removes that
/// term (`subtract_model_variance`): it minimises Σ w_j (measured_j − model_j(θ))² − Σ w_j
/// var_j(θ), with var_j the model's own unbiased variance estimate under the same random numbers
/// (the second sum enters Ceres as one extra residual √(C − Σ w_j var_j(θ)) with a constant C;
/// its derivatives come from the same finite-difference evaluations, so it costs no model
/// evaluation).

#include <Eigen/Core>
#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "tirpol/fitting/solver_termination.h"

namespace tirpol::fitting {

/// One evaluation of a noisy model: its values and the variance of each (same length).
struct NoisyPrediction {
    std::vector<double> value;
    std::vector<double> variance;
};

/// The model: predictions at the given parameter values. Must be deterministic in its parameters
/// (common random numbers). May throw; the fit stops and rethrows.
using NoisyModel = std::function<NoisyPrediction(const std::vector<double>& parameters)>;

enum class FiniteDifference {
    central,  ///< (f(θ+h) − f(θ−h))/2h: error O(h²), 2 evaluations per parameter
    forward,  ///< (f(θ+h) − f(θ))/h: error O(h), 1 evaluation per parameter
};

struct NoisyModelFitOptions {
    std::vector<std::string> names;  ///< one per parameter, for reports and errors
    std::vector<double> initial, lower, upper;
    /// Finite-difference step per parameter (> 0), in the parameter's units; a step that would
    /// leave the bounds turns the difference one-sided at that point.
    std::vector<double> steps;
    FiniteDifference differences = FiniteDifference::central;
    int max_iterations = 30;  ///< per solve
    bool reweight =
        true;  ///< re-evaluate the model variances at the first solution and solve again
    /// Subtract Σ w_j var_j(θ) from the objective (above), so that the model's noise does not pull
    /// the minimum towards less noisy parameters. Off: the plain weighted least squares.
    bool subtract_model_variance = true;
    /// Called after every model evaluation with the number made so far (progress bars).
    std::function<void(int evaluations)> on_evaluation;
    /// Checked before every model evaluation; once set the fit throws tirpol::Cancelled. Null:
    /// never.
    const std::atomic<bool>* cancel = nullptr;
};

struct NoisyModelFitResult {
    std::vector<double> values;
    std::vector<double> sigma;  ///< √diag(covariance); 0 when the covariance is unavailable
    Eigen::MatrixXd
        covariance;  ///< (JᵀWJ)⁻¹ at the solution, W from measurement and model variance
    Eigen::MatrixXd correlation;
    bool covariance_available = false;
    std::vector<double> model;                 ///< model values at the solution
    std::vector<double> model_variance;        ///< their variances (the weights of the last solve)
    std::vector<double> normalized_residuals;  ///< (measured − model)/√(σ_meas² + σ_model²)
    double chi2 = 0.0;
    int dof = 0;  ///< residuals − parameters
    double reduced_chi2 = 0.0;
    bool usable = false;            ///< ceres::Solver::Summary::IsSolutionUsable of the last solve
    SolverTermination termination;  ///< of the last solve
    std::string solver_report;
    int iterations = 0;   ///< over all solves
    int evaluations = 0;  ///< model evaluations, the finite differences included
    /// −½ (JᵀWJ)⁻¹ ∇_θ Σ w_j var_j(θ) at the solution: the first-order shift of the plain weighted
    /// least squares' minimum by the model's variance (what `subtract_model_variance` removes);
    /// empty when the covariance is unavailable.
    std::vector<double> model_variance_shift;
    std::vector<std::string>
        warnings;  ///< parameters on a bound, rank-deficient Jacobian, χ²/dof > 3
};

/// Fits `model` to `measured` (σ `measured_sigma`, > 0 each). Throws tirpol::Error on inconsistent
/// sizes, a bound or step that is not finite or ordered, fewer residuals than parameters + 1, or a
/// model evaluation of the wrong size or with a non-finite value.
NoisyModelFitResult fit_noisy_model(const NoisyModel& model, const std::vector<double>& measured,
                                    const std::vector<double>& measured_sigma,
                                    const NoisyModelFitOptions& options);

}  // namespace tirpol::fitting
