// Least squares of a noisy black-box model with finite-difference derivatives (noisy_model_fit.h).

#include <ceres/ceres.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <map>
#include <memory>

#include "ceres_termination.h"
#include "tirpol/core/error.h"
#include "tirpol/core/interrupt_signals.h"
#include "tirpol/fitting/render_fit.h"

namespace tirpol::fitting {

namespace {

void validate(const std::vector<double>& measured, const std::vector<double>& measured_sigma,
              const NoisyModelFitOptions& o) {
    const std::size_t p = o.initial.size();
    if (p == 0) fail("noisy model fit: no parameters to fit");
    if (o.names.size() != p || o.lower.size() != p || o.upper.size() != p || o.steps.size() != p)
        fail(
            "noisy model fit: names, initial, lower, upper and steps must have one entry per "
            "parameter ({})",
            p);
    if (measured.size() != measured_sigma.size())
        fail("noisy model fit: {} measured values but {} uncertainties", measured.size(),
             measured_sigma.size());
    if (measured.size() < p + 1)
        fail("noisy model fit: {} residuals for {} free parameters; expected at least {}",
             measured.size(), p, p + 1);
    for (std::size_t j = 0; j < measured.size(); ++j)
        if (!std::isfinite(measured[j]) || !(measured_sigma[j] > 0.0) ||
            !std::isfinite(measured_sigma[j]))
            fail(
                "noisy model fit: measured value {} is {} ± {}; expected a finite value with a "
                "finite σ > 0",
                j, measured[j], measured_sigma[j]);
    for (std::size_t i = 0; i < p; ++i) {
        if (!std::isfinite(o.lower[i]) || !std::isfinite(o.upper[i]) || !(o.lower[i] < o.upper[i]))
            fail("noisy model fit: parameter {}: bounds [{}, {}] are not finite and ordered",
                 o.names[i], o.lower[i], o.upper[i]);
        if (!(o.initial[i] >= o.lower[i] && o.initial[i] <= o.upper[i]))
            fail("noisy model fit: parameter {}: initial value {} outside its bounds [{}, {}]",
                 o.names[i], o.initial[i], o.lower[i], o.upper[i]);
        if (!(o.steps[i] > 0.0) || !(o.steps[i] < o.upper[i] - o.lower[i]))
            fail(
                "noisy model fit: parameter {}: finite-difference step {} must be > 0 and below "
                "the bounds' width {}",
                o.names[i], o.steps[i], o.upper[i] - o.lower[i]);
    }
    if (o.max_iterations < 1)
        fail("noisy model fit: max_iterations must be at least 1, got {}", o.max_iterations);
}

/// Evaluates the model once per distinct parameter vector (Ceres asks for residuals and Jacobian at
/// the same point separately), checks every prediction, counts evaluations.
class ModelEvaluator {
public:
    ModelEvaluator(const NoisyModel& model, std::size_t size, const NoisyModelFitOptions& options)
        : m_model(model), m_size(size), m_options(options) {}

    const NoisyPrediction& operator()(const std::vector<double>& theta) {
        if (auto it = m_cache.find(theta); it != m_cache.end()) return it->second;
        throw_if_cancelled(m_options.cancel, "fit through the renderer");
        NoisyPrediction p = m_model(theta);
        if (p.value.size() != m_size || p.variance.size() != m_size)
            fail("noisy model fit: the model returned {} values and {} variances; expected {}",
                 p.value.size(), p.variance.size(), m_size);
        for (std::size_t j = 0; j < m_size; ++j)
            if (!std::isfinite(p.value[j]) || !std::isfinite(p.variance[j]) || p.variance[j] < 0.0)
                fail(
                    "noisy model fit: the model's value {} is {} with variance {} at parameters "
                    "({}); expected "
                    "finite values and variances ≥ 0",
                    j, p.value[j], p.variance[j], fmt::join(theta, ", "));
        ++m_evaluations;
        if (m_options.on_evaluation) m_options.on_evaluation(m_evaluations);
        // Only the last few points are asked again (residuals, then the Jacobian there).
        if (m_cache.size() > 64) m_cache.clear();
        return m_cache.emplace(theta, std::move(p)).first->second;
    }
    int evaluations() const { return m_evaluations; }

private:
    const NoisyModel& m_model;
    std::size_t m_size;
    const NoisyModelFitOptions& m_options;
    std::map<std::vector<double>, NoisyPrediction> m_cache;
    int m_evaluations = 0;
};

/// A cost over the model, with fixed σ, that keeps an exception from the model instead of letting
/// it cross Ceres: the evaluation is reported as failed, the callback then stops the solver and the
/// fit rethrows it.
class ModelCost : public ceres::CostFunction {
public:
    ModelCost(ModelEvaluator& evaluate, const std::vector<double>& sigma,
              const NoisyModelFitOptions& options, std::exception_ptr& error, int residual_count)
        : m_evaluate(evaluate), m_sigma(sigma), m_options(options), m_error(error) {
        set_num_residuals(residual_count);
        mutable_parameter_block_sizes()->push_back(static_cast<int>(options.initial.size()));
    }

    bool Evaluate(double const* const* parameters, double* residuals,
                  double** jacobians) const final {
        if (m_error) return false;
        try {
            const std::vector<double> theta(parameters[0],
                                            parameters[0] + m_options.initial.size());
            return evaluate_at(theta, residuals, jacobians);
        } catch (...) {
            m_error = std::current_exception();
            return false;
        }
    }

protected:
    /// The residuals at `theta` and, when `jacobians` asks for them, their derivatives (row-major);
    /// false rejects the step.
    virtual bool evaluate_at(const std::vector<double>& theta, double* residuals,
                             double** jacobians) const = 0;

    ModelEvaluator& m_evaluate;
    const std::vector<double>& m_sigma;
    const NoisyModelFitOptions& m_options;

private:
    std::exception_ptr& m_error;
};

/// Whitened residuals (measured − model)/σ with fixed σ, derivatives by finite differences.
class FiniteDifferenceCost final : public ModelCost {
public:
    FiniteDifferenceCost(ModelEvaluator& evaluate, const std::vector<double>& measured,
                         const std::vector<double>& sigma, const NoisyModelFitOptions& options,
                         std::exception_ptr& error)
        : ModelCost(evaluate, sigma, options, error, static_cast<int>(measured.size())),
          m_measured(measured) {}

private:
    bool evaluate_at(const std::vector<double>& theta, double* residuals,
                     double** jacobians) const override {
        const std::size_t p = m_options.initial.size(), m = m_measured.size();
        const NoisyPrediction& at = m_evaluate(theta);
        for (std::size_t j = 0; j < m; ++j)
            residuals[j] = (m_measured[j] - at.value[j]) / m_sigma[j];
        if (!jacobians || !jacobians[0]) return true;
        const std::vector<double> center = at.value;  // the cache may drop `at` while differencing
        for (std::size_t i = 0; i < p; ++i) {
            const double h = m_options.steps[i];
            const bool up_ok = theta[i] + h <= m_options.upper[i],
                       down_ok = theta[i] - h >= m_options.lower[i];
            std::vector<double> plus = theta, minus = theta;
            plus[i] += h;
            minus[i] -= h;
            std::vector<double> d(m);
            if (m_options.differences == FiniteDifference::central && up_ok && down_ok) {
                const std::vector<double> fp = m_evaluate(plus).value;
                const std::vector<double>& fm = m_evaluate(minus).value;
                for (std::size_t j = 0; j < m; ++j) d[j] = (fp[j] - fm[j]) / (2.0 * h);
            } else if (up_ok) {
                const std::vector<double>& fp = m_evaluate(plus).value;
                for (std::size_t j = 0; j < m; ++j) d[j] = (fp[j] - center[j]) / h;
            } else {
                const std::vector<double>& fm = m_evaluate(minus).value;
                for (std::size_t j = 0; j < m; ++j) d[j] = (center[j] - fm[j]) / h;
            }
            // Row-major m × p; residual = (measured − model)/σ, so ∂r/∂θ = −∂model/∂θ / σ.
            for (std::size_t j = 0; j < m; ++j) jacobians[0][j * p + i] = -d[j] / m_sigma[j];
        }
        return true;
    }

    const std::vector<double>& m_measured;
};

/// Σ_j w_j var_j(θ) of a model evaluation.
double weighted_variance(const NoisyPrediction& at, const std::vector<double>& sigma) {
    double sum = 0.0;
    for (std::size_t j = 0; j < sigma.size(); ++j) sum += at.variance[j] / (sigma[j] * sigma[j]);
    return sum;
}

/// Finite-difference gradient of Σ_j w_j var_j(θ) with the data's stencil (the same points, so the
/// evaluator's cache answers them without a model evaluation).
std::vector<double> weighted_variance_gradient(ModelEvaluator& evaluate,
                                               const std::vector<double>& theta,
                                               const std::vector<double>& sigma,
                                               const NoisyModelFitOptions& o) {
    const double center = weighted_variance(evaluate(theta), sigma);
    std::vector<double> gradient(theta.size());
    for (std::size_t i = 0; i < theta.size(); ++i) {
        const double h = o.steps[i];
        const bool up_ok = theta[i] + h <= o.upper[i], down_ok = theta[i] - h >= o.lower[i];
        std::vector<double> plus = theta, minus = theta;
        plus[i] += h;
        minus[i] -= h;
        if (o.differences == FiniteDifference::central && up_ok && down_ok)
            gradient[i] = (weighted_variance(evaluate(plus), sigma) -
                           weighted_variance(evaluate(minus), sigma)) /
                          (2.0 * h);
        else if (up_ok)
            gradient[i] = (weighted_variance(evaluate(plus), sigma) - center) / h;
        else
            gradient[i] = (center - weighted_variance(evaluate(minus), sigma)) / h;
    }
    return gradient;
}

/// The objective's variance term as one residual, r² = C − Σ_j w_j var_j(θ) (noisy_model_fit.h):
/// a constant C > Σ w var keeps it real; Ceres then minimises the data's squares minus Σ w var.
class ModelVarianceCost final : public ModelCost {
public:
    ModelVarianceCost(ModelEvaluator& evaluate, const std::vector<double>& sigma, double constant,
                      const NoisyModelFitOptions& options, std::exception_ptr& error)
        : ModelCost(evaluate, sigma, options, error, 1), m_constant(constant) {}

private:
    bool evaluate_at(const std::vector<double>& theta, double* residuals,
                     double** jacobians) const override {
        const std::size_t p = m_options.initial.size();
        const double squared = m_constant - weighted_variance(m_evaluate(theta), m_sigma);
        // Σ w var beyond C (a far step to a much noisier point): the cost is then not this
        // objective, and Ceres rejects the step.
        if (!(squared > 0.0)) return false;
        residuals[0] = std::sqrt(squared);
        if (!jacobians || !jacobians[0]) return true;
        const std::vector<double> gradient =
            weighted_variance_gradient(m_evaluate, theta, m_sigma, m_options);
        for (std::size_t i = 0; i < p; ++i) jacobians[0][i] = -gradient[i] / (2.0 * residuals[0]);
        return true;
    }

    double m_constant;
};

class StopOnError final : public ceres::IterationCallback {
public:
    explicit StopOnError(const std::exception_ptr& error) : m_error(error) {}
    ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
        return m_error ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
    }

private:
    const std::exception_ptr& m_error;
};

std::vector<double> total_sigma(const std::vector<double>& measured_sigma,
                                const std::vector<double>& model_variance) {
    std::vector<double> s(measured_sigma.size());
    for (std::size_t j = 0; j < s.size(); ++j)
        s[j] = std::sqrt(measured_sigma[j] * measured_sigma[j] + model_variance[j]);
    return s;
}

}  // namespace

NoisyModelFitResult fit_noisy_model(const NoisyModel& model, const std::vector<double>& measured,
                                    const std::vector<double>& measured_sigma,
                                    const NoisyModelFitOptions& options) {
    validate(measured, measured_sigma, options);
    const std::size_t p = options.initial.size(), m = measured.size();
    ModelEvaluator evaluate(model, m, options);
    std::exception_ptr error;
    NoisyModelFitResult result;
    std::vector<double> theta = options.initial;
    std::vector<double> sigma;
    std::unique_ptr<ceres::Problem> problem;

    const int solves = options.reweight ? 2 : 1;
    for (int solve = 0; solve < solves; ++solve) {
        // Weights from the model's variance where this solve starts, held for the whole solve.
        sigma = total_sigma(measured_sigma, evaluate(theta).variance);
        ceres::Problem::Options po;
        problem = std::make_unique<ceres::Problem>(po);
        problem->AddResidualBlock(
            new FiniteDifferenceCost(evaluate, measured, sigma, options, error), nullptr,
            theta.data());
        if (options.subtract_model_variance) {
            // C: four times the start's Σ w var plus one per residual (Σ w var ≤ m at the
            // start), so steps to a few times noisier renders stay inside the objective.
            const double constant =
                4.0 * weighted_variance(evaluate(theta), sigma) + static_cast<double>(m);
            problem->AddResidualBlock(
                new ModelVarianceCost(evaluate, sigma, constant, options, error), nullptr,
                theta.data());
        }
        for (std::size_t i = 0; i < p; ++i) {
            problem->SetParameterLowerBound(theta.data(), static_cast<int>(i), options.lower[i]);
            problem->SetParameterUpperBound(theta.data(), static_cast<int>(i), options.upper[i]);
        }
        ceres::Solver::Options so;
        so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
        so.linear_solver_type = ceres::DENSE_QR;
        so.max_num_iterations = options.max_iterations;
        // The model is smooth only to its Monte Carlo jitter: stop at changes the data cannot see.
        so.function_tolerance = 1e-4;
        so.gradient_tolerance = 1e-10;
        so.parameter_tolerance = 1e-4;
        so.logging_type = ceres::SILENT;
        StopOnError stop(error);
        so.callbacks.push_back(&stop);
        ceres::Solver::Summary summary;
        ceres::Solve(so, problem.get(), &summary);
        if (error) std::rethrow_exception(error);
        result.usable = summary.IsSolutionUsable();
        result.termination = termination_of(summary);
        result.solver_report = summary.BriefReport();
        result.iterations += static_cast<int>(summary.iterations.size());
    }

    // Covariance (JᵀWJ)⁻¹ at the solution, with the weights of the last solve, from the data's
    // residuals alone (the variance term is not a measurement).
    ceres::Problem data_problem;
    data_problem.AddResidualBlock(
        new FiniteDifferenceCost(evaluate, measured, sigma, options, error), nullptr, theta.data());
    ceres::Covariance::Options co;
    co.algorithm_type = ceres::DENSE_SVD;
    co.null_space_rank = -1;
    ceres::Covariance covariance(co);
    const std::vector<std::pair<const double*, const double*>> blocks{{theta.data(), theta.data()}};
    const bool have_covariance = covariance.Compute(blocks, &data_problem);
    if (error) std::rethrow_exception(error);
    const auto n = static_cast<Eigen::Index>(p);
    result.covariance = Eigen::MatrixXd::Zero(n, n);
    result.correlation = Eigen::MatrixXd::Identity(n, n);
    result.std_uncertainty.assign(p, 0.0);
    if (have_covariance) {
        Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> c(n, n);
        covariance.GetCovarianceBlock(theta.data(), theta.data(), c.data());
        result.covariance = c;
        result.covariance_available = true;
        for (Eigen::Index i = 0; i < n; ++i)
            result.std_uncertainty[static_cast<std::size_t>(i)] = std::sqrt(c(i, i));
        const std::vector<double> gradient =
            weighted_variance_gradient(evaluate, theta, sigma, options);
        const Eigen::VectorXd shift =
            -0.5 * c * Eigen::Map<const Eigen::VectorXd>(gradient.data(), n);
        result.model_variance_shift.assign(shift.data(), shift.data() + n);
        for (Eigen::Index i = 0; i < n; ++i)
            for (Eigen::Index j = 0; j < n; ++j) {
                const double d = std::sqrt(c(i, i) * c(j, j));
                if (i != j) result.correlation(i, j) = d > 0.0 ? c(i, j) / d : 0.0;
            }
        if ((c.diagonal().array() <= 0.0).any())
            result.warnings.push_back(
                "the Jacobian is rank-deficient at the solution: some parameter does not change "
                "the residuals "
                "(σ from the pseudo-inverse, not reliable)");
    } else {
        result.warnings.push_back(
            "covariance could not be computed: uncertainties are unavailable");
    }

    const NoisyPrediction& at = evaluate(theta);
    result.values = theta;
    result.model = at.value;
    result.model_variance.resize(m);
    result.normalized_residuals.resize(m);
    for (std::size_t j = 0; j < m; ++j) {
        result.model_variance[j] = sigma[j] * sigma[j] - measured_sigma[j] * measured_sigma[j];
        result.normalized_residuals[j] = (measured[j] - at.value[j]) / sigma[j];
        result.chi2 += result.normalized_residuals[j] * result.normalized_residuals[j];
    }
    result.dof = static_cast<int>(m) - static_cast<int>(p);
    result.reduced_chi2 = result.chi2 / result.dof;
    result.evaluations = evaluate.evaluations();
    for (std::size_t i = 0; i < p; ++i) {
        const double width = options.upper[i] - options.lower[i];
        if (theta[i] - options.lower[i] < 1e-6 * width ||
            options.upper[i] - theta[i] < 1e-6 * width)
            result.warnings.push_back(fmt::format(
                "{} sits on a bound ({}): its σ is not meaningful", options.names[i], theta[i]));
    }
    if (result.reduced_chi2 > 3.0)
        result.warnings.push_back(fmt::format(
            "χ²/dof = {:.2f}: the model does not describe the data within their uncertainties",
            result.reduced_chi2));
    if (!result.usable)
        result.warnings.push_back("the solver did not reach a usable solution: " +
                                  result.termination.text());
    return result;
}

}  // namespace tirpol::fitting
