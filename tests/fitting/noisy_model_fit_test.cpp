// Least squares of a noisy model (fitting/noisy_model_fit.h): the covariance against the closed
// form of weighted linear least squares, and the coverage of its σ when the model's own Monte Carlo
// noise (common random numbers: one fixed offset per fit) enters the weights — Press et al.,
// Numerical Recipes 3rd ed., §15.4–15.5.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <atomic>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "error_of.h"
#include "tirpol/core/error.h"
#include "tirpol/core/interrupt_signals.h"
#include "tirpol/fitting/render_fit.h"

using tirpol::test::error_of;

using namespace tirpol;
using namespace tirpol::fitting;

namespace {

NoisyModelFitOptions two_parameter_options(double a0, double b0) {
    NoisyModelFitOptions o;
    o.names = {"a", "b"};
    o.initial = {a0, b0};
    o.lower = {-10.0, -10.0};
    o.upper = {10.0, 10.0};
    o.steps = {1e-3, 1e-3};
    return o;
}

}  // namespace

// A straight line y = a + b·x with measurement σ_m and a model variance σ_s² at every point: the
// fit's covariance must be the closed form (XᵀWX)⁻¹ with W = 1/(σ_m² + σ_s²), and its values the
// weighted normal equations' solution to 1 % of σ (finite differences are exact for a linear
// model).
TEST(NoisyModelFit, LinearModelCovarianceIsTheClosedForm) {
    const int m = 12;
    const double sigma_m = 0.1, sigma_s = 0.05;
    std::vector<double> x(m), y(m), sy(m, sigma_m);
    std::mt19937_64 rng(3);
    std::normal_distribution<double> noise(0.0, sigma_m);
    for (int i = 0; i < m; ++i) x[i] = i, y[i] = 1.5 + 0.3 * i + noise(rng);
    const NoisyModel line = [&](const std::vector<double>& t) {
        NoisyPrediction p;
        for (int i = 0; i < m; ++i)
            p.value.push_back(t[0] + t[1] * x[i]), p.variance.push_back(sigma_s * sigma_s);
        return p;
    };
    const NoisyModelFitResult r = fit_noisy_model(line, y, sy, two_parameter_options(0.0, 0.0));
    ASSERT_TRUE(r.usable) << r.termination;
    ASSERT_TRUE(r.covariance_available);

    Eigen::MatrixXd X(m, 2);
    Eigen::VectorXd Y(m);
    for (int i = 0; i < m; ++i) X(i, 0) = 1.0, X(i, 1) = x[i], Y(i) = y[i];
    const double w = 1.0 / (sigma_m * sigma_m + sigma_s * sigma_s);
    const Eigen::Matrix2d expected = (w * X.transpose() * X).inverse();
    const Eigen::Vector2d solution = expected * (w * X.transpose() * Y);
    for (int i = 0; i < 2; ++i) {
        // The solver stops at relative parameter changes of 1e-4 (noisy models: finer is noise), so
        // the values agree to a small fraction of their σ, the covariance to rounding.
        EXPECT_NEAR(r.values[i], solution(i), 0.01 * std::sqrt(expected(i, i)));
        for (int j = 0; j < 2; ++j)
            EXPECT_NEAR(r.covariance(i, j), expected(i, j), 1e-6 * std::abs(expected(i, i)));
    }
    EXPECT_EQ(r.dof, m - 2);
    EXPECT_NEAR(r.std_uncertainty[1], std::sqrt(expected(1, 1)), 1e-9);
}

// Repeated fits of a nonlinear model y = A·exp(−x/τ) whose every evaluation carries the same Monte
// Carlo offset (common random numbers, drawn anew for each fit with σ_s comparable to σ_m). With
// the model variance in the weights, the pulls (θ̂ − θ)/σ have unit spread and ⟨χ²/dof⟩ ≈ 1; with
// it left out, σ is too small and the pulls spread by √(1 + σ_s²/σ_m²) ≈ 1.4.
TEST(NoisyModelFit, RenderNoiseInTheWeightsGivesPullsOfUnitSpread) {
    const int m = 15, fits = 200;
    const double a_true = 2.0, tau_true = 4.0, sigma_m = 0.02, sigma_s = 0.02;
    std::mt19937_64 rng(11);
    std::normal_distribution<double> normal(0.0, 1.0);
    const auto pull_spread = [&](bool model_variance_known, double* mean_reduced_chi2) {
        double sum2 = 0.0, chi2 = 0.0;
        for (int f = 0; f < fits; ++f) {
            std::vector<double> y(m), sy(m, sigma_m), offset(m);
            for (int i = 0; i < m; ++i) {
                y[i] = a_true * std::exp(-i / tau_true) + sigma_m * normal(rng);
                offset[i] = sigma_s * normal(rng);  // the render's noise, fixed by its seed
            }
            const NoisyModel model = [&](const std::vector<double>& t) {
                NoisyPrediction p;
                for (int i = 0; i < m; ++i) {
                    p.value.push_back(t[0] * std::exp(-i / t[1]) + offset[i]);
                    p.variance.push_back(model_variance_known ? sigma_s * sigma_s : 0.0);
                }
                return p;
            };
            NoisyModelFitOptions o = two_parameter_options(1.5, 3.0);
            o.lower = {0.1, 0.5};
            o.steps = {1e-4, 1e-4};
            const NoisyModelFitResult r = fit_noisy_model(model, y, sy, o);
            EXPECT_TRUE(r.usable);
            const double pull = (r.values[1] - tau_true) / r.std_uncertainty[1];
            sum2 += pull * pull;
            chi2 += r.reduced_chi2;
        }
        *mean_reduced_chi2 = chi2 / fits;
        return std::sqrt(sum2 / fits);
    };
    double chi2_known = 0.0, chi2_ignored = 0.0;
    const double with = pull_spread(true, &chi2_known), without = pull_spread(false, &chi2_ignored);
    // 200 fits: the spread of a unit-variance sample is known to ±0.05 (1σ).
    EXPECT_NEAR(with, 1.0, 0.15);
    EXPECT_NEAR(chi2_known, 1.0, 0.15);
    EXPECT_GT(without, 1.25);
    EXPECT_NEAR(chi2_ignored, 2.0, 0.3);
}

// A model whose Monte Carlo error grows with the parameter, as a render's does when a wider lobe
// samples more of the surroundings: y = θ·(1 + s·ε_i) with ε_i fixed per fit (common random
// numbers), variance (θ·s)². Averaged over ε the plain objective Σ w (y − model)² carries Σ w θ²s²,
// which pulls its minimum to θ/(1 + s²) (−0.83 σ here); subtracting the model's variance removes
// the pull, and model_variance_shift predicts it.
TEST(NoisyModelFit, SubtractingTheModelVarianceRemovesItsPullOnTheMinimum) {
    const int m = 10, fits = 300;
    const double theta_true = 1.0, sigma_m = 0.1, s = 0.3;
    std::mt19937_64 rng(17);
    std::normal_distribution<double> normal(0.0, 1.0);
    double pull_plain = 0.0, pull_subtracted = 0.0, shift_predicted = 0.0, shift_seen = 0.0;
    for (int f = 0; f < fits; ++f) {
        std::vector<double> y(m), sy(m, sigma_m), eps(m);
        for (int i = 0; i < m; ++i) y[i] = theta_true + sigma_m * normal(rng), eps[i] = normal(rng);
        const NoisyModel model = [&](const std::vector<double>& t) {
            NoisyPrediction p;
            for (int i = 0; i < m; ++i) {
                p.value.push_back(t[0] * (1.0 + s * eps[i]));
                p.variance.push_back(t[0] * t[0] * s * s);
            }
            return p;
        };
        NoisyModelFitOptions o;
        o.names = {"theta"};
        o.initial = {0.8};
        o.lower = {0.1};
        o.upper = {3.0};
        o.steps = {1e-3};
        o.subtract_model_variance = false;
        const NoisyModelFitResult plain = fit_noisy_model(model, y, sy, o);
        o.subtract_model_variance = true;
        const NoisyModelFitResult subtracted = fit_noisy_model(model, y, sy, o);
        ASSERT_TRUE(plain.usable && subtracted.usable) << subtracted.termination;
        ASSERT_EQ(subtracted.model_variance_shift.size(), 1u);
        pull_plain += (plain.values[0] - theta_true) / plain.std_uncertainty[0] / fits;
        pull_subtracted +=
            (subtracted.values[0] - theta_true) / subtracted.std_uncertainty[0] / fits;
        shift_predicted += subtracted.model_variance_shift[0] / fits;
        shift_seen += (plain.values[0] - subtracted.values[0]) / fits;
    }
    // 300 fits: a mean pull is known to ±0.06 (1σ).
    EXPECT_LT(pull_plain, -0.6);
    EXPECT_NEAR(pull_subtracted, 0.0, 0.2);
    EXPECT_NEAR(shift_seen, shift_predicted, 0.2 * std::abs(shift_predicted));
}

TEST(NoisyModelFit, BadInputNamesTheParameterAndWhatWasExpected) {
    const NoisyModel flat = [](const std::vector<double>& t) {
        return NoisyPrediction{{t[0], t[0], t[1]}, {0.0, 0.0, 0.0}};
    };
    const std::vector<double> y{1.0, 1.0, 2.0}, sy{0.1, 0.1, 0.1};
    auto o = two_parameter_options(0.0, 0.0);
    o.initial[1] = 20.0;
    EXPECT_NE(error_of([&] {
                  fit_noisy_model(flat, y, sy, o);
              }).find("b: initial value 20 outside its bounds"),
              std::string::npos);
    o = two_parameter_options(0.0, 0.0);
    o.steps[0] = 0.0;
    EXPECT_NE(
        error_of([&] { fit_noisy_model(flat, y, sy, o); }).find("a: finite-difference step 0"),
        std::string::npos);
    o = two_parameter_options(0.0, 0.0);
    EXPECT_NE(error_of([&] {
                  fit_noisy_model(flat, y, {0.1, 0.0, 0.1}, o);
              }).find("finite σ > 0"),
              std::string::npos);
    EXPECT_NE(error_of([&] {
                  fit_noisy_model(flat, {1.0, 2.0}, {0.1, 0.1}, o);
              }).find("expected at least 3"),
              std::string::npos);
    const NoisyModel short_model = [](const std::vector<double>&) {
        return NoisyPrediction{{1.0}, {0.0}};
    };
    EXPECT_NE(error_of([&] { fit_noisy_model(short_model, y, sy, o); }).find("expected 3"),
              std::string::npos);
}

TEST(NoisyModelFit, AModelErrorOrACancelStopsTheFit) {
    const std::vector<double> y{1.0, 1.0, 2.0}, sy{0.1, 0.1, 0.1};
    int calls = 0;
    const NoisyModel failing = [&](const std::vector<double>& t) {
        if (++calls > 3) fail("render failed at a = {}", t[0]);
        return NoisyPrediction{{t[0], t[0], t[1]}, {0.0, 0.0, 0.0}};
    };
    EXPECT_NE(error_of([&] {
                  fit_noisy_model(failing, y, sy, two_parameter_options(0.0, 0.0));
              }).find("render failed"),
              std::string::npos);
    std::atomic<bool> cancel{true};
    auto o = two_parameter_options(0.0, 0.0);
    o.cancel = &cancel;
    const NoisyModel fine = [](const std::vector<double>& t) {
        return NoisyPrediction{{t[0], t[0], t[1]}, {0.0, 0.0, 0.0}};
    };
    EXPECT_THROW(fit_noisy_model(fine, y, sy, o), Cancelled);
}
