#pragma once
/// \file render_fit.h
/// Fit of pBRDF parameters through the renderer (analysis by synthesis): the scene is rendered with
/// candidate parameters of one or more micro-facet materials, from every measured view (its own
/// camera model and pose), and the simulated Stokes are compared with the measured ones directly,
///   minimise Σ (S_meas − S_sim(θ))² / (σ_meas² + σ_sim²)
/// over region means (or pixels) of S0, S1, S2, with Ceres (noisy_model_fit.h). Unlike the
/// emissivity fit (paper eq 17 then microfacet_fit.h) it needs no uniform downwelling: whatever the
/// scene holds — a sky that is colder at the zenith, a warm ground, a reflector at its own
/// temperature — is rendered. It needs instead everything the render needs: geometry, temperatures,
/// sky, camera model and pose.
///
/// Every evaluation renders with the same seed (common random numbers), so the objective is a
/// smooth function of the parameters up to the sampler's branch decisions; finite differences step
/// by much more than that jitter (render_fit.cpp). The render's own Monte Carlo variance enters the
/// weights, so the covariance includes it. The renderer's S*_var channels give σ_sim.
///
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
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/core/image.h"
#include "tirpol/fitting/microfacet_fit.h"
#include "tirpol/simulation/pinhole_camera.h"
#include "tirpol/simulation/scene.h"

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
    /// Standard uncertainties √diag(covariance); 0 when the covariance is unavailable.
    std::vector<double> std_uncertainty;
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

/// A parameter of a scene material to fit. The material must be micro-facet
/// (materials/microfacet.h); fitting n or k needs a constant (not tabulated) refractive index.
struct RenderFitParameter {
    std::string material;  ///< name in Scene::materials
    MicrofacetParameter parameter = MicrofacetParameter::n;
    double lower = 0.0, upper = 0.0;
    std::optional<double> initial;  ///< unset: the scene material's own value
    /// Finite-difference step in the parameter's units; unset: 2 % of the initial value's
    /// magnitude, at least 1 % of the bounds' width (render_fit.cpp says why).
    std::optional<double> step;
};

/// Pixels to compare, row-major indices (y·width + x) of the view's image.
struct RenderFitRegion {
    std::string name;
    std::vector<std::size_t> pixels;
};

/// One measured view.
struct RenderFitView {
    std::string name;
    simulation::PinholeCamera
        camera;  ///< the measuring camera's model and pose; its size is the image's
    /// Measured Stokes in the camera frame of ARCHITECTURE.md, W/(m²·sr): channels S0 S1 S2 and
    /// their per-pixel standard uncertainties S0_std S1_std S2_std (what calibration's reduction
    /// writes).
    Image measured;
    std::vector<RenderFitRegion> regions;
};

enum class RenderFitResiduals {
    region_means,  ///< one residual per view, region and Stokes component (region mean, σ of the
                   ///< mean)
    pixels,        ///< one per pixel of every region and Stokes component
};

struct RenderFitOptions {
    std::vector<RenderFitParameter> parameters;
    std::vector<int> stokes = {0, 1, 2};  ///< which of S0, S1, S2 to compare
    RenderFitResiduals residuals = RenderFitResiduals::region_means;
    int samples_per_pixel = 0;          ///< 0: the scene's
    std::optional<std::uint64_t> seed;  ///< the one seed of every evaluation; unset: the scene's
    FiniteDifference differences = FiniteDifference::central;
    int max_iterations = 20;
    bool reweight = true;  ///< NoisyModelFitOptions::reweight
    /// NoisyModelFitOptions::subtract_model_variance: remove the render variance's pull on the
    /// minimum (noisy_model_fit.h).
    bool subtract_model_variance = true;
    int threads = 0;             ///< render threads (0: all cores)
    bool show_progress = false;  ///< a progress bar of the renders on stderr (core/progress.h)
    const std::atomic<bool>* cancel =
        nullptr;  ///< checked before every render; then throws tirpol::Cancelled
    /// Emissivity-table cache folder for the first render (simulation::RenderOptions); later
    /// renders keep tables in memory only, so the candidate materials' tables do not fill the disk
    /// cache.
    std::optional<std::filesystem::path> emissivity_cache_dir;
};

/// A fitted parameter.
struct RenderFitParameterResult {
    std::string material;
    std::string name;  ///< "n", "sigma", …
    double initial = 0.0, value = 0.0, lower = 0.0, upper = 0.0, step = 0.0;
    double std_uncertainty = 0.0;  ///< standard uncertainty of `value` (0 without covariance)
    /// NoisyModelFitResult::model_variance_shift: how far the render's variance would pull a plain
    /// least-squares minimum (removed when subtract_model_variance is set); 0 without covariance.
    double variance_shift = 0.0;
};

/// One compared value at the solution.
struct RenderFitComparison {
    std::size_t view = 0, region = 0;
    int stokes = 0;
    std::size_t pixel = 0;  ///< pixel index (RenderFitResiduals::pixels), else 0
    double measured = 0.0, simulated = 0.0, sigma_measured = 0.0, sigma_simulated = 0.0;
    double normalized_residual = 0.0;  ///< (measured − simulated)/√(σ_meas² + σ_sim²)
};

struct RenderFitSummary {
    std::vector<RenderFitParameterResult> parameters;
    Eigen::MatrixXd covariance, correlation;  ///< of `parameters`, in their order
    bool covariance_available = false;
    double chi2 = 0.0;
    int dof = 0;
    double reduced_chi2 = 0.0;
    std::vector<RenderFitComparison> comparisons;
    bool usable = false;  ///< Ceres' IsSolutionUsable of the last solve
    SolverTermination termination;
    std::string solver_report;
    int iterations = 0;
    int renders = 0;  ///< scene renders (each evaluation renders every view)
    double seconds = 0.0;
    std::vector<std::string> warnings;

    bool IsSolutionUsable() const { return usable; }
    /// Parameters with 1σ, χ²/dof, renders, time, termination and warnings, as text.
    std::string FullReport() const;
};

/// Fits `options.parameters` of `scene`'s materials to the measured `views`. Throws tirpol::Error
/// on bad input (unknown material or a non-micro-facet one, a tabulated index for n or k, a view
/// whose image and camera sizes differ, a missing channel, an empty region or a pixel outside the
/// image, bounds that do not hold the initial value), tirpol::Cancelled when cancelled.
RenderFitSummary fit_through_renderer(const simulation::Scene& scene,
                                      const std::vector<RenderFitView>& views,
                                      const RenderFitOptions& options);

/// The interior of an object in a render (channel `object_id`): its pixels whose 8 neighbours show
/// it too, so the region holds no pixel mixed with another surface. Empty if the object is not
/// visible.
RenderFitRegion object_region(const Image& render, std::size_t object_index, std::string name);

/// Regions of the named objects as `camera` sees them: a geometry render of the scene (1 sample per
/// pixel; the object_id channel is the pixel-centre ray's), then object_region of each. Throws
/// tirpol::Error naming an object that the scene lacks or that covers no interior pixel.
std::vector<RenderFitRegion> object_regions(const simulation::Scene& scene,
                                            const simulation::PinholeCamera& camera,
                                            const std::vector<std::string>& objects);

/// A measured view from files: the Stokes EXR (S0 S1 S2 S0_std S1_std S2_std, as `tirpol reduce`
/// writes it) seen through the camera model and pose YAMLs (core/camera_model.h) or, when both
/// paths are empty, through the scene's camera resized to the image; the regions of `objects`.
RenderFitView load_render_fit_view(const simulation::Scene& scene,
                                   const std::filesystem::path& measured_exr,
                                   const std::filesystem::path& camera_model,
                                   const std::filesystem::path& pose,
                                   const std::vector<std::string>& objects);

/// "MATERIAL.PARAMETER=LOWER:UPPER" or "MATERIAL.PARAMETER=LOWER:UPPER:INITIAL" (the CLI's --free),
/// e.g. "flat_black_paint.sigma=0.05:1". Throws tirpol::Error quoting the text and what was
/// expected.
RenderFitParameter parse_render_fit_parameter(const std::string& text);

/// `tirpol fit-render` as text: the scene file, each measured view as "MEASURED.exr" (the scene's
/// camera) or "MEASURED.exr,CAMERA.yaml,POSE.yaml", the objects whose regions are compared, and the
/// free parameters as parse_render_fit_parameter reads them (filling `fit.parameters`).
struct RenderFitRunOptions {
    std::filesystem::path scene;
    std::vector<std::string> views, objects, free;
    RenderFitOptions fit;
};

/// Reads every text and file of `options` (tirpol::OptionValueError naming --free or --view for
/// text of the wrong form, checked before any file is read) and runs fit_through_renderer.
RenderFitSummary run_render_fit(const RenderFitRunOptions& options);

/// The scene's material named `material` with the given micro-facet parameters replaced (the same
/// spectral values elsewhere). Throws as fit_through_renderer does for bad materials or parameters.
std::shared_ptr<const materials::PolarizedBrdf> microfacet_with(
    const simulation::Scene& scene, const std::string& material,
    const std::vector<std::pair<MicrofacetParameter, double>>& values);

}  // namespace tirpol::fitting
