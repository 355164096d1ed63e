#include "tirpol/fitting/microfacet_fit.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "ceres_termination.h"
#include "emissivity_residual.h"
#include "latin_hypercube.h"
#include "tirpol/core/error.h"
#include "tirpol/core/interrupt_signals.h"
#include "tirpol/core/limits.h"

namespace tirpol::fitting {

namespace {

constexpr std::array<std::string_view, kMicrofacetParameterCount> kNames = {
    "n", "k", "sigma", "bias", "tau_deg", "omega_deg", "rho_d", "rho_v"};

std::size_t to_index(MicrofacetParameter p) { return static_cast<std::size_t>(p); }

// Relative χ² tolerance within which a start counts as having reached the best minimum.
bool same_minimum(double chi2, double best) { return chi2 <= best * (1.0 + 1e-6) + 1e-9; }

}  // namespace

std::string_view parameter_name(MicrofacetParameter p) { return kNames[to_index(p)]; }

MicrofacetParameter parameter_from_name(std::string_view name) {
    for (std::size_t i = 0; i < kNames.size(); ++i)
        if (kNames[i] == name) return static_cast<MicrofacetParameter>(i);
    fail(
        "unknown micro-facet parameter \"{}\"; expected one of n, k, sigma, bias, tau_deg, "
        "omega_deg, rho_d, rho_v",
        name);
}

std::array<ParameterSetting, kMicrofacetParameterCount> default_parameter_settings() {
    return {{
        {1.5, 1.05, 4.0, false},        // n
        {0.1, 0.0, 2.0, false},         // k
        {0.2, 0.05, 1.0, false},        // sigma
        {1.0, 0.0, 1.0, true},          // bias
        {90.0, 1.0, 180.0, true},       // tau_deg
        {1e6, 1.0, 1e6, true},          // omega_deg
        {0.01, 0.0, 1.0 / kPi, false},  // rho_d
        {0.0, 0.0, 1.0, true},          // rho_v
    }};
}

const FittedParameter& MicrofacetFitResult::get(MicrofacetParameter p, std::size_t band) const {
    const bool per_band = p == MicrofacetParameter::n || p == MicrofacetParameter::k;
    std::size_t seen = 0;
    for (const FittedParameter& f : parameters) {
        if (f.kind != p) continue;
        if (!per_band || seen++ == band) return f;
    }
    fail("fit result has no parameter {} for band {}", parameter_name(p), band);
}

materials::ShellTargetParameters<double> MicrofacetFitResult::model_parameters(
    std::size_t band) const {
    std::array<double, kMicrofacetParameterCount> values{};
    for (std::size_t i = 0; i < kMicrofacetParameterCount; ++i)
        values[i] = get(static_cast<MicrofacetParameter>(i), band).value;
    return model_parameters_from_fit_order(values);
}

std::array<double, kMicrofacetParameterCount> fit_order_values(
    const materials::ShellTargetParameters<double>& p) {
    return {p.n,     p.k,    p.sigma, p.bias, rad_to_deg(p.tau_rad), rad_to_deg(p.omega_rad),
            p.rho_d, p.rho_v};
}

struct MicrofacetFitProblem::Impl {
    std::vector<EmissivityDataset> datasets;
    MicrofacetFitOptions options;
    std::vector<double> wavelengths;
    std::vector<std::size_t> dataset_band;
    // One entry per measured sample, in dataset order.
    std::vector<std::unique_ptr<EmissivityQuadrature>> quadratures;
    std::vector<std::pair<std::size_t, std::size_t>> sample_of;  // (dataset, sample)
    std::vector<std::unique_ptr<ceres::CostFunction>> costs;

    std::size_t band_count() const { return wavelengths.size(); }
    std::size_t value_count() const { return 2 * band_count() + kMicrofacetParameterCount - 2; }

    // Index into the value vector of parameter `p` for band `band`: per-band n, k first, then
    // shared.
    std::size_t value_index(MicrofacetParameter p, std::size_t band) const {
        if (p == MicrofacetParameter::n) return 2 * band;
        if (p == MicrofacetParameter::k) return 2 * band + 1;
        return 2 * band_count() + to_index(p) - 2;
    }
    MicrofacetParameter kind_of(std::size_t value) const {
        if (value < 2 * band_count())
            return value % 2 == 0 ? MicrofacetParameter::n : MicrofacetParameter::k;
        return static_cast<MicrofacetParameter>(value - 2 * band_count() + 2);
    }
    std::optional<std::size_t> band_of(std::size_t value) const {
        if (value < 2 * band_count()) return value / 2;
        return std::nullopt;
    }
    const ParameterSetting& setting(std::size_t value) const {
        return options.parameters[to_index(kind_of(value))];
    }

    std::string value_name(std::size_t value) const {
        const std::string base(parameter_name(kind_of(value)));
        const auto band = band_of(value);
        if (!band || band_count() == 1) return base;
        return fmt::format("{}@{:g}um", base, wavelengths[*band]);
    }

    std::vector<std::size_t> free_values() const {
        std::vector<std::size_t> out;
        for (std::size_t v = 0; v < value_count(); ++v)
            if (!setting(v).fixed) out.push_back(v);
        return out;
    }

    std::array<double*, kMicrofacetParameterCount> blocks_for(std::vector<double>& values,
                                                              std::size_t band) const {
        std::array<double*, kMicrofacetParameterCount> out{};
        for (std::size_t p = 0; p < kMicrofacetParameterCount; ++p)
            out[p] = &values[value_index(static_cast<MicrofacetParameter>(p), band)];
        return out;
    }

    // A Ceres problem over `values` (which must outlive it). `for_solving`: fixed parameters
    // constant and bounds set; otherwise every block is variable (for evaluation and covariance of
    // all columns).
    std::unique_ptr<ceres::Problem> build(std::vector<double>& values, bool for_solving) const {
        ceres::Problem::Options po;
        po.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
        auto problem = std::make_unique<ceres::Problem>(po);
        for (std::size_t v = 0; v < value_count(); ++v) problem->AddParameterBlock(&values[v], 1);
        for (std::size_t r = 0; r < costs.size(); ++r) {
            const auto blocks = blocks_for(values, dataset_band[sample_of[r].first]);
            problem->AddResidualBlock(costs[r].get(), nullptr,
                                      std::vector<double*>(blocks.begin(), blocks.end()));
        }
        if (for_solving)
            for (std::size_t v = 0; v < value_count(); ++v) {
                const ParameterSetting& s = setting(v);
                if (s.fixed) {
                    problem->SetParameterBlockConstant(&values[v]);
                } else {
                    problem->SetParameterLowerBound(&values[v], 0, s.lower);
                    problem->SetParameterUpperBound(&values[v], 0, s.upper);
                }
            }
        return problem;
    }

    std::vector<double> initial_values() const {
        std::vector<double> values(value_count());
        for (std::size_t v = 0; v < value_count(); ++v) values[v] = setting(v).initial;
        return values;
    }

    // Starting points: the initial values, then a Latin hypercube over the free parameters' bounds
    // (log-uniform for a positive range spanning more than two decades, e.g. Ω).
    std::vector<std::vector<double>> start_points() const {
        const std::vector<std::size_t> free = free_values();
        std::vector<std::vector<double>> starts = {initial_values()};
        const auto extra = static_cast<std::size_t>(std::max(0, options.starts - 1));
        const auto design = detail::latin_hypercube(extra, free.size(), options.seed);
        for (const auto& unit : design) {
            std::vector<double> values = initial_values();
            for (std::size_t d = 0; d < free.size(); ++d) {
                const ParameterSetting& s = setting(free[d]);
                const bool logarithmic = s.lower > 0.0 && s.upper / s.lower > 100.0;
                values[free[d]] = logarithmic ? s.lower * std::pow(s.upper / s.lower, unit[d])
                                              : s.lower + unit[d] * (s.upper - s.lower);
            }
            starts.push_back(std::move(values));
        }
        return starts;
    }

    ceres::Solver::Options solver_options() const {
        ceres::Solver::Options so;
        so.minimizer_type = ceres::TRUST_REGION;
        so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
        so.linear_solver_type = ceres::DENSE_QR;
        so.max_num_iterations = options.max_iterations;
        so.function_tolerance = 1e-12;
        so.gradient_tolerance = 1e-12;
        so.parameter_tolerance = 1e-10;
        so.logging_type = ceres::SILENT;
        so.num_threads = std::max(1, options.threads);
        return so;
    }

    void covariance(MicrofacetFitResult& result, std::vector<double>& best) const {
        const std::vector<std::size_t> free = free_values();
        auto problem = build(best, true);
        std::vector<std::pair<const double*, const double*>> pairs;
        for (std::size_t i = 0; i < free.size(); ++i)
            for (std::size_t j = i; j < free.size(); ++j)
                pairs.emplace_back(&best[free[i]], &best[free[j]]);

        // SPARSE_QR drops the constant (fixed) blocks' columns and fails on a rank-deficient
        // Jacobian; DENSE_SVD would see the fixed blocks as zero columns, so it serves only as the
        // fallback.
        ceres::Covariance::Options co;
        co.algorithm_type = ceres::SPARSE_QR;
        co.num_threads = 1;
        auto cov = std::make_unique<ceres::Covariance>(co);
        bool ok = cov->Compute(pairs, problem.get());
        if (!ok) {
            // Rank-deficient Jacobian: some combination of parameters does not change the
            // residuals. The Moore–Penrose pseudo-inverse still gives the uncertainty of the
            // identifiable part.
            co.algorithm_type = ceres::DENSE_SVD;
            co.null_space_rank = -1;
            cov = std::make_unique<ceres::Covariance>(co);
            ok = cov->Compute(pairs, problem.get());
            result.warnings.push_back(
                "the Jacobian is rank-deficient at the minimum: the data do not determine every "
                "free parameter; "
                "uncertainties come from the pseudo-inverse and are not reliable (fix one of the "
                "correlated "
                "parameters with --fix)");
        }
        if (!ok) {
            result.warnings.push_back(
                "covariance could not be computed: uncertainties are unavailable");
            return;
        }
        const auto n = static_cast<Eigen::Index>(free.size());
        result.covariance = Eigen::MatrixXd::Zero(n, n);
        for (Eigen::Index i = 0; i < n; ++i)
            for (Eigen::Index j = i; j < n; ++j) {
                double c = 0.0;
                cov->GetCovarianceBlock(&best[free[static_cast<std::size_t>(i)]],
                                        &best[free[static_cast<std::size_t>(j)]], &c);
                result.covariance(i, j) = result.covariance(j, i) = c;
            }
        if (options.scale_covariance_by_reduced_chi2 && result.dof > 0) {
            result.covariance *= result.reduced_chi2;
            result.covariance_scaled = true;
        }
        result.correlation = Eigen::MatrixXd::Identity(n, n);
        for (Eigen::Index i = 0; i < n; ++i)
            for (Eigen::Index j = 0; j < n; ++j) {
                const double d = std::sqrt(result.covariance(i, i) * result.covariance(j, j));
                if (i != j) result.correlation(i, j) = d > 0.0 ? result.covariance(i, j) / d : 0.0;
            }
        result.covariance_available = true;
    }
};

MicrofacetFitProblem::MicrofacetFitProblem(std::vector<EmissivityDataset> datasets,
                                           MicrofacetFitOptions options)
    : m(std::make_unique<Impl>()) {
    if (datasets.empty()) fail("no emissivity data to fit");
    for (const EmissivityDataset& d : datasets) validate_dataset(d);
    if (options.starts < 1 || options.starts > limits::kMaxFitStarts)
        fail("--starts: expected 1 to {} starts (limits.h), got {}", limits::kMaxFitStarts,
             options.starts);
    if (options.max_iterations < 1)
        fail("max_iterations: expected at least 1, got {}", options.max_iterations);
    std::size_t free = 0;
    for (std::size_t p = 0; p < kMicrofacetParameterCount; ++p) {
        const ParameterSetting& s = options.parameters[p];
        const std::string_view name = kNames[p];
        if (!std::isfinite(s.initial) || !std::isfinite(s.lower) || !std::isfinite(s.upper))
            fail("parameter {}: initial value and bounds must be finite (got {} in [{}, {}])", name,
                 s.initial, s.lower, s.upper);
        if (!(s.lower <= s.initial && s.initial <= s.upper))
            fail("parameter {}: value {} lies outside its bounds [{}, {}]", name, s.initial,
                 s.lower, s.upper);
        if (!s.fixed && !(s.lower < s.upper))
            fail("parameter {}: a free parameter needs lower < upper (got [{}, {}])", name, s.lower,
                 s.upper);
        if (!s.fixed) ++free;
    }
    if (free == 0) fail("every parameter is fixed: nothing to fit (free some with --free)");

    m->options = options;
    m->datasets = std::move(datasets);
    std::map<double, std::size_t> band_of_wavelength;
    for (const EmissivityDataset& d : m->datasets) band_of_wavelength.emplace(d.wavelength_um, 0);
    for (auto& [wavelength, band] : band_of_wavelength) {
        band = m->wavelengths.size();
        m->wavelengths.push_back(wavelength);
    }
    for (std::size_t di = 0; di < m->datasets.size(); ++di) {
        const EmissivityDataset& d = m->datasets[di];
        m->dataset_band.push_back(band_of_wavelength.at(d.wavelength_um));
        for (std::size_t si = 0; si < d.samples.size(); ++si) {
            m->quadratures.push_back(std::make_unique<EmissivityQuadrature>(
                deg_to_rad(d.samples[si].angle_deg), options.quadrature));
            m->sample_of.emplace_back(di, si);
            m->costs.push_back(detail::make_cost_function(
                {m->quadratures.back().get(), d.samples[si]}, options.derivatives));
        }
    }
    const std::size_t free_values = m->free_values().size();
    if (residual_count() <= free_values)
        fail(
            "{} samples give {} residuals (ε_S0 and ε_S1 per angle) for {} free parameters: a fit "
            "needs more "
            "residuals than free parameters; measure more angles or fix parameters with --fix",
            m->costs.size(), residual_count(), free_values);
}

MicrofacetFitProblem::~MicrofacetFitProblem() = default;
MicrofacetFitProblem::MicrofacetFitProblem(MicrofacetFitProblem&&) noexcept = default;
MicrofacetFitProblem& MicrofacetFitProblem::operator=(MicrofacetFitProblem&&) noexcept = default;

std::vector<std::string> MicrofacetFitProblem::parameter_names() const {
    std::vector<std::string> out;
    for (std::size_t v = 0; v < m->value_count(); ++v) out.push_back(m->value_name(v));
    return out;
}
std::vector<double> MicrofacetFitProblem::initial_values() const { return m->initial_values(); }
std::size_t MicrofacetFitProblem::residual_count() const { return 2 * m->costs.size(); }
std::size_t MicrofacetFitProblem::free_parameter_count() const { return m->free_values().size(); }
const std::vector<EmissivityDataset>& MicrofacetFitProblem::datasets() const { return m->datasets; }
const std::vector<double>& MicrofacetFitProblem::wavelengths_um() const { return m->wavelengths; }

void MicrofacetFitProblem::evaluate(const std::vector<double>& values,
                                    std::vector<double>* residuals,
                                    std::vector<double>* jacobian) const {
    if (values.size() != m->value_count())
        fail("evaluate: expected {} parameter values, got {}", m->value_count(), values.size());
    std::vector<double> work = values;
    // Fixed parameters are constant blocks, as in the fit: Ceres leaves their columns zero and does
    // not differentiate with respect to them, so the cost of a call is the cost of one fit
    // iteration.
    auto problem = m->build(work, true);
    ceres::Problem::EvaluateOptions eo;
    for (double& v : work) eo.parameter_blocks.push_back(&v);
    std::vector<double> r;
    ceres::CRSMatrix crs;
    double cost = 0.0;
    problem->Evaluate(eo, &cost, &r, nullptr, jacobian ? &crs : nullptr);
    if (residuals) *residuals = r;
    if (jacobian) {
        jacobian->assign(r.size() * values.size(), 0.0);
        for (int row = 0; row < crs.num_rows; ++row)
            for (int i = crs.rows[static_cast<std::size_t>(row)];
                 i < crs.rows[static_cast<std::size_t>(row) + 1]; ++i) {
                const auto col = static_cast<std::size_t>(crs.cols[static_cast<std::size_t>(i)]);
                (*jacobian)[static_cast<std::size_t>(row) * values.size() + col] =
                    crs.values[static_cast<std::size_t>(i)];
            }
    }
}

GradientCheckReport MicrofacetFitProblem::check_gradients(const std::vector<double>& values,
                                                          double relative_precision) const {
    if (values.size() != m->value_count())
        fail("check_gradients: expected {} parameter values, got {}", m->value_count(),
             values.size());
    GradientCheckReport report;
    // GradientChecker differentiates numerically by Ridders' extrapolation; its default first step
    // (1 % of the value) is too coarse for the Gaussian tails of D(θN) in σ and biases the estimate
    // by ~1e-3.
    ceres::NumericDiffOptions nd;
    nd.ridders_relative_initial_step_size = 1e-3;
    std::vector<double> work = values;
    for (std::size_t r = 0; r < m->costs.size(); ++r) {
        const auto blocks = m->blocks_for(work, m->dataset_band[m->sample_of[r].first]);
        std::array<const double*, kMicrofacetParameterCount> params{};
        std::copy(blocks.begin(), blocks.end(), params.begin());
        const ceres::GradientChecker checker(
            m->costs[r].get(), static_cast<const std::vector<const ceres::Manifold*>*>(nullptr),
            nd);
        ceres::GradientChecker::ProbeResults results;
        const bool ok = checker.Probe(params.data(), relative_precision, &results);
        report.worst_relative_error =
            std::max(report.worst_relative_error, results.maximum_relative_error);
        if (!ok && report.ok) {
            report.ok = false;
            report.first_error = results.error_log;
        }
    }
    return report;
}

namespace {

/// Ends a Ceres solve at the next iteration once the caller's cancellation flag is set.
class AbortWhenCancelled final : public ceres::IterationCallback {
public:
    explicit AbortWhenCancelled(const std::atomic<bool>* cancel) : m_cancel(cancel) {}
    ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
        return m_cancel && m_cancel->load(std::memory_order_relaxed) ? ceres::SOLVER_ABORT
                                                                     : ceres::SOLVER_CONTINUE;
    }

private:
    const std::atomic<bool>* m_cancel;
};

}  // namespace

MicrofacetFitResult MicrofacetFitProblem::solve() const {
    const Impl& im = *m;
    MicrofacetFitResult result;
    result.wavelengths_um = im.wavelengths;
    const std::vector<std::size_t> free = im.free_values();

    std::vector<double> best;
    double best_chi2 = std::numeric_limits<double>::infinity();
    bool best_usable = false;
    for (const std::vector<double>& start : im.start_points()) {
        std::vector<double> values = start;
        auto problem = im.build(values, true);
        throw_if_cancelled(im.options.cancel, "micro-facet fit");
        AbortWhenCancelled abort_when_cancelled(im.options.cancel);
        ceres::Solver::Options solver_options = im.solver_options();
        solver_options.callbacks.push_back(&abort_when_cancelled);
        ceres::Solver::Summary summary;
        ceres::Solve(solver_options, problem.get(), &summary);
        throw_if_cancelled(im.options.cancel, "micro-facet fit");
        StartOutcome outcome;
        outcome.initial = start;
        outcome.chi2 = 2.0 * summary.final_cost;
        outcome.usable = summary.IsSolutionUsable() && std::isfinite(summary.final_cost);
        outcome.termination = termination_of(summary);
        outcome.iterations = static_cast<int>(summary.iterations.size());
        result.residual_evaluations += std::max(0, summary.num_residual_evaluations);
        result.jacobian_evaluations += std::max(0, summary.num_jacobian_evaluations);
        // Prefer usable solutions; among them the lowest χ².
        if ((outcome.usable && !best_usable) ||
            (outcome.usable == best_usable && outcome.chi2 < best_chi2)) {
            best = values;
            best_chi2 = outcome.chi2;
            best_usable = outcome.usable;
            result.termination = outcome.termination;
            result.solver_report = summary.BriefReport();
        }
        result.starts.push_back(std::move(outcome));
    }
    result.usable = best_usable;
    std::size_t reached = 0;
    for (StartOutcome& s : result.starts) {
        s.reached_best = s.usable && same_minimum(s.chi2, best_chi2);
        if (s.reached_best) ++reached;
    }
    result.fraction_reaching_best =
        static_cast<double>(reached) / static_cast<double>(result.starts.size());
    if (!best_usable)
        result.warnings.push_back("no start gave a usable solution (" + result.termination.text() +
                                  "): the parameters below are not a fit");

    // Non-finite residuals make Ceres' covariance factorise a matrix of NaN (Eigen's JacobiSVD then
    // crashed): a solution that is not finite is an error, and only a usable one gets a covariance.
    if (!std::isfinite(best_chi2) ||
        !std::all_of(best.begin(), best.end(), [](double v) { return std::isfinite(v); }))
        fail(
            "the fit gave no finite solution (chi2 = {}, {}): check the data for values far "
            "outside the model's "
            "range",
            best_chi2, result.termination);
    result.chi2 = best_chi2;
    result.dof = static_cast<int>(residual_count()) - static_cast<int>(free.size());
    result.reduced_chi2 = result.chi2 / result.dof;
    if (best_usable)
        im.covariance(result, best);
    else
        result.warnings.push_back(
            "covariance not computed: the solution is not usable, so uncertainties are "
            "unavailable");

    for (std::size_t v = 0; v < im.value_count(); ++v) {
        const ParameterSetting& s = im.setting(v);
        FittedParameter f;
        f.name = im.value_name(v);
        f.kind = im.kind_of(v);
        if (const auto band = im.band_of(v); band && im.band_count() > 1)
            f.wavelength_um = im.wavelengths[*band];
        f.value = best[v];
        f.fixed = s.fixed;
        f.lower = s.lower;
        f.upper = s.upper;
        f.at_bound = !s.fixed &&
                     std::min(f.value - s.lower, s.upper - f.value) <= 1e-6 * (s.upper - s.lower);
        result.parameters.push_back(f);
    }
    for (std::size_t i = 0; i < free.size(); ++i) {
        result.free_indices.push_back(free[i]);
        if (result.covariance_available) {
            const auto ii = static_cast<Eigen::Index>(i);
            result.parameters[free[i]].std_uncertainty =
                std::sqrt(std::max(0.0, result.covariance(ii, ii)));
        }
    }

    // Warnings a person must see next to the numbers.
    for (const FittedParameter& f : result.parameters)
        if (f.at_bound)
            result.warnings.push_back(
                fmt::format("{} = {:g} sits on a bound of [{:g}, {:g}]: its uncertainty is not "
                            "meaningful (the fit wants to go "
                            "further; widen the bound or fix it)",
                            f.name, f.value, f.lower, f.upper));
    if (result.covariance_available)
        for (std::size_t i = 0; i < free.size(); ++i)
            for (std::size_t j = i + 1; j < free.size(); ++j) {
                const double rho =
                    result.correlation(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
                if (std::abs(rho) > im.options.correlation_warning)
                    result.warnings.push_back(fmt::format(
                        "{} and {} are degenerate (correlation {:+.3f}): the data constrain a "
                        "combination of them "
                        "rather than each; consider fixing one (--fix)",
                        result.parameters[free[i]].name, result.parameters[free[j]].name, rho));
            }
    if (result.dof > 0 && result.reduced_chi2 > 3.0)
        result.warnings.push_back(fmt::format(
            "chi2/dof = {:.2f} is well above 1: the model does not describe the data within the "
            "stated uncertainties "
            "(or they are underestimated; --scale-covariance scales the covariance by chi2/dof)",
            result.reduced_chi2));

    // Per-sample model values and whitened residuals at the best fit.
    for (std::size_t r = 0; r < im.costs.size(); ++r) {
        const auto [di, si] = im.sample_of[r];
        const EmissivitySample& s = im.datasets[di].samples[si];
        const auto [s0, s1] =
            im.quadratures[r]->emissivity(result.model_parameters(im.dataset_band[di]));
        result.samples.push_back({di, si, s.angle_deg, s0, s1, (s0 - s.eps_s0) / s.eps_s0_std,
                                  (s1 - s.eps_s1) / s.eps_s1_std});
    }
    return result;
}

}  // namespace tirpol::fitting
