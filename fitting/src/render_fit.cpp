// Fit of micro-facet parameters through the renderer (render_fit.h).

#include "tirpol/fitting/render_fit.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <optional>

#include "tirpol/core/camera_model.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/log.h"
#include "tirpol/materials/microfacet.h"
#include "tirpol/simulation/renderer.h"

namespace tirpol::fitting {

namespace {

constexpr const char* kStokes[] = {"S0", "S1", "S2"};

std::size_t material_index(const simulation::Scene& scene, const std::string& name) {
    std::string names;
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        if (scene.materials[i].name == name) return i;
        names += (i ? ", " : "") + scene.materials[i].name;
    }
    fail("fit through the renderer: the scene {} has no material named '{}' (materials: {})",
         scene.file.string(), name, names);
}

const materials::MicrofacetBrdf& microfacet_of(const simulation::Scene& scene,
                                               const std::string& material) {
    const auto* brdf = dynamic_cast<const materials::MicrofacetBrdf*>(
        scene.materials[material_index(scene, material)].brdf.get());
    if (!brdf)
        fail(
            "fit through the renderer: material '{}' is the {} model; only micro-facet materials "
            "can be fitted",
            material, scene.materials[material_index(scene, material)].brdf->model());
    return *brdf;
}

/// A constant spectral value of `material`, or an error: a fit of one number cannot stand for a
/// table.
double constant_value(const materials::SpectralValue& v, const std::string& material,
                      MicrofacetParameter p) {
    if (!v.is_constant())
        fail(
            "fit through the renderer: {} of material '{}' varies with wavelength; only constant "
            "values can be fitted",
            parameter_name(p), material);
    return v.at(10.0);
}

double current_value(const materials::MicrofacetBrdf& brdf, const std::string& material,
                     MicrofacetParameter p) {
    const materials::MicrofacetParameters& mp = brdf.spectral_parameters();
    switch (p) {
        case MicrofacetParameter::n:
        case MicrofacetParameter::k: {
            if (!mp.index.is_constant())
                fail(
                    "fit through the renderer: material '{}' has a tabulated refractive index "
                    "({}); n and k can be "
                    "fitted only for a constant index",
                    material, mp.index.source());
            const materials::ComplexIndex index = mp.index.at(10.0);
            return p == MicrofacetParameter::n ? index.n : index.k;
        }
        case MicrofacetParameter::sigma:
            return constant_value(mp.sigma, material, p);
        case MicrofacetParameter::bias:
            return constant_value(mp.bias, material, p);
        case MicrofacetParameter::tau_deg:
            return constant_value(mp.tau_deg, material, p);
        case MicrofacetParameter::omega_deg:
            return constant_value(mp.omega_deg, material, p);
        case MicrofacetParameter::rho_d:
            return constant_value(mp.rho_d, material, p);
        case MicrofacetParameter::rho_v:
            return constant_value(mp.rho_v, material, p);
    }
    fail("fit through the renderer: unknown parameter");
}

/// Where the variance of an image's values comes from, and how residuals per pixel take it.
struct VarianceSource {
    const char* suffix;  ///< the variance channel: S0 + suffix, …
    bool is_std;         ///< the channel holds a standard deviation, not a variance
    /// Residuals per pixel take the region's mean variance instead of each pixel's own estimate
    /// (render_fit.cpp's fit_through_renderer says why a render's needs it).
    bool pooled_over_region;
};

/// A measurement's per-pixel σ (`tirpol reduce`'s S*_std, from many frames): each pixel's own.
constexpr VarianceSource kMeasuredStd{"_std", true, false};
/// A render's per-pixel variance (S*_var, from its replicates): pooled over the region.
constexpr VarianceSource kRenderVariance{"_var", false, true};

/// Region means (or pixels) of the chosen Stokes components, and their variances from `source`,
/// in the fixed order view, region, component, pixel.
void append_values(const Image& image, const RenderFitView& view, const RenderFitOptions& options,
                   const VarianceSource& source, std::vector<double>& values,
                   std::vector<double>& variances) {
    for (const RenderFitRegion& region : view.regions)
        for (int k : options.stokes) {
            const auto& s = image.channel(kStokes[k]);
            const auto& v = image.channel(std::string(kStokes[k]) + source.suffix);
            const auto var = [&](std::size_t i) {
                const double x = v[i];
                return source.is_std ? x * x : x;
            };
            // Pixels are independent (their own random numbers, their own temporal noise): the
            // variance of the mean is Σ var/n².
            double sum = 0.0, sum_var = 0.0;
            for (std::size_t i : region.pixels) sum += s[i], sum_var += var(i);
            const auto n = static_cast<double>(region.pixels.size());
            if (options.residuals == RenderFitResiduals::pixels) {
                for (std::size_t i : region.pixels)
                    values.push_back(s[i]),
                        variances.push_back(source.pooled_over_region ? sum_var / n : var(i));
                continue;
            }
            values.push_back(sum / n);
            variances.push_back(sum_var / (n * n));
        }
}

void validate_views(const std::vector<RenderFitView>& views, const RenderFitOptions& options) {
    if (views.empty()) fail("fit through the renderer: no measured view");
    if (options.stokes.empty()) fail("fit through the renderer: no Stokes component to compare");
    for (int k : options.stokes)
        if (k < 0 || k > 2)
            fail("fit through the renderer: Stokes component {} (expected 0, 1 or 2)", k);
    for (const RenderFitView& v : views) {
        const Image& m = v.measured;
        if (m.width() != v.camera.width() || m.height() != v.camera.height())
            fail("fit through the renderer: view '{}': measured image {}×{} but camera {}×{}",
                 v.name, m.width(), m.height(), v.camera.width(), v.camera.height());
        for (int k : options.stokes)
            for (const std::string& c : {std::string(kStokes[k]), std::string(kStokes[k]) + "_std"})
                if (!m.has_channel(c))
                    fail(
                        "fit through the renderer: view '{}': the measured image has no channel {} "
                        "(expected S0 S1 "
                        "S2 and S0_std S1_std S2_std)",
                        v.name, c);
        if (v.regions.empty())
            fail("fit through the renderer: view '{}' has no region to compare", v.name);
        const std::size_t size =
            static_cast<std::size_t>(m.width()) * static_cast<std::size_t>(m.height());
        for (const RenderFitRegion& r : v.regions) {
            if (r.pixels.empty())
                fail("fit through the renderer: view '{}': region '{}' is empty", v.name, r.name);
            for (std::size_t i : r.pixels) {
                if (i >= size)
                    fail(
                        "fit through the renderer: view '{}': region '{}' has pixel {} outside the "
                        "{}×{} image",
                        v.name, r.name, i, m.width(), m.height());
                for (int k : options.stokes) {
                    const double s = m.channel(kStokes[k])[i],
                                 sd = m.channel(std::string(kStokes[k]) + "_std")[i];
                    if (!std::isfinite(s) || !std::isfinite(sd) || !(sd > 0.0))
                        fail(
                            "fit through the renderer: view '{}': region '{}': pixel ({}, {}) has "
                            "{} = {} ± {}; "
                            "expected a finite value with a finite σ > 0",
                            v.name, r.name, i % static_cast<std::size_t>(m.width()),
                            i / static_cast<std::size_t>(m.width()), kStokes[k], s, sd);
                }
            }
        }
    }
}

/// The default step: well above the render's jitter between parameter values (the sampler's branch
/// decisions move with the parameters even with common random numbers), small enough that the
/// curvature of ε(n, σ) over 2h stays below the noise: 2 % of the value, at least 1 % of the range.
double default_step(double initial, double lower, double upper) {
    return std::max(0.02 * std::abs(initial), 0.01 * (upper - lower));
}

}  // namespace

std::shared_ptr<const materials::PolarizedBrdf> microfacet_with(
    const simulation::Scene& scene, const std::string& material,
    const std::vector<std::pair<MicrofacetParameter, double>>& values) {
    const materials::MicrofacetBrdf& brdf = microfacet_of(scene, material);
    materials::MicrofacetParameters mp = brdf.spectral_parameters();
    for (const auto& [p, value] : values) {
        current_value(brdf, material, p);  // refuses tables
        switch (p) {
            case MicrofacetParameter::n:
            case MicrofacetParameter::k: {
                materials::ComplexIndex index = mp.index.at(10.0);
                (p == MicrofacetParameter::n ? index.n : index.k) = value;
                mp.index = materials::RefractiveIndexTable::constant(index, mp.index.source());
                break;
            }
            case MicrofacetParameter::sigma:
                mp.sigma = value;
                break;
            case MicrofacetParameter::bias:
                mp.bias = value;
                break;
            case MicrofacetParameter::tau_deg:
                mp.tau_deg = value;
                break;
            case MicrofacetParameter::omega_deg:
                mp.omega_deg = value;
                break;
            case MicrofacetParameter::rho_d:
                mp.rho_d = value;
                break;
            case MicrofacetParameter::rho_v:
                mp.rho_v = value;
                break;
        }
    }
    return std::make_shared<materials::MicrofacetBrdf>(std::move(mp));
}

RenderFitRegion object_region(const Image& render, std::size_t object_index, std::string name) {
    RenderFitRegion region{std::move(name), {}};
    const auto& id = render.channel("object_id");
    const auto object = static_cast<float>(object_index);
    for (int y = 1; y + 1 < render.height(); ++y)
        for (int x = 1; x + 1 < render.width(); ++x) {
            bool inside = true;
            for (int dy = -1; dy <= 1 && inside; ++dy)
                for (int dx = -1; dx <= 1 && inside; ++dx)
                    inside = id[render.index(x + dx, y + dy)] == object;
            if (inside) region.pixels.push_back(render.index(x, y));
        }
    return region;
}

std::vector<RenderFitRegion> object_regions(const simulation::Scene& scene,
                                            const simulation::PinholeCamera& camera,
                                            const std::vector<std::string>& objects) {
    simulation::Scene geometry = scene;
    geometry.camera = camera;
    geometry.sampling.samples_per_pixel = 1;
    const Image render = simulation::render(geometry);
    std::vector<RenderFitRegion> regions;
    for (const std::string& name : objects) {
        std::size_t index = scene.objects.size();
        std::string names;
        for (std::size_t i = 0; i < scene.objects.size(); ++i) {
            if (scene.objects[i].name == name) index = i;
            names += (i ? ", " : "") + scene.objects[i].name;
        }
        if (index == scene.objects.size())
            fail("fit through the renderer: the scene {} has no object named '{}' (objects: {})",
                 scene.file.string(), name, names);
        regions.push_back(object_region(render, index, name));
        if (regions.back().pixels.empty())
            fail("fit through the renderer: object '{}' covers no interior pixel of the {}×{} view",
                 name, camera.width(), camera.height());
    }
    return regions;
}

RenderFitView load_render_fit_view(const simulation::Scene& scene,
                                   const std::filesystem::path& measured_exr,
                                   const std::filesystem::path& camera_model,
                                   const std::filesystem::path& pose,
                                   const std::vector<std::string>& objects) {
    const std::string name = measured_exr.filename().string();
    Image measured = read_exr(measured_exr);
    if (camera_model.empty() != pose.empty())
        fail("fit through the renderer: view {}: give both a camera model and a pose, or neither",
             name);
    const simulation::PinholeCamera camera =
        camera_model.empty() ? scene.camera.resized(measured.width(), measured.height())
                             : simulation::PinholeCamera::from_model(
                                   read_camera_model(camera_model), read_camera_pose(pose));
    RenderFitView view{name, camera, std::move(measured), {}};
    view.regions = object_regions(scene, view.camera, objects);
    return view;
}

RenderFitParameter parse_render_fit_parameter(const std::string& text) {
    const auto dot = text.find('.'), eq = text.find('=');
    const auto bad = [&](const std::string& why) {
        fail(
            "'{}': {}; expected MATERIAL.PARAMETER=LOWER:UPPER[:INITIAL], e.g. "
            "flat_black_paint.sigma=0.05:1",
            text, why);
    };
    if (dot == std::string::npos || eq == std::string::npos || eq < dot)
        bad("no MATERIAL.PARAMETER= part");
    RenderFitParameter p;
    p.material = text.substr(0, dot);
    if (p.material.empty()) bad("no material name");
    p.parameter = parameter_from_name(text.substr(dot + 1, eq - dot - 1));
    std::vector<double> numbers;
    std::size_t from = eq + 1;
    while (true) {
        const auto colon = text.find(':', from);
        const std::string part =
            text.substr(from, colon == std::string::npos ? std::string::npos : colon - from);
        const std::optional<double> v = parse_number(part);
        if (!v || !std::isfinite(*v)) bad(fmt::format("'{}' is not a number", part));
        numbers.push_back(*v);
        if (colon == std::string::npos) break;
        from = colon + 1;
    }
    if (numbers.size() != 2 && numbers.size() != 3) bad(fmt::format("{} numbers", numbers.size()));
    p.lower = numbers[0];
    p.upper = numbers[1];
    if (numbers.size() == 3) p.initial = numbers[2];
    return p;
}

RenderFitSummary fit_through_renderer(const simulation::Scene& scene,
                                      const std::vector<RenderFitView>& views,
                                      const RenderFitOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    validate_views(views, options);
    if (options.parameters.empty()) fail("fit through the renderer: no parameter to fit");
    if (options.samples_per_pixel < 0)
        fail("fit through the renderer: samples per pixel {} (expected ≥ 1, or 0 for the scene's)",
             options.samples_per_pixel);

    NoisyModelFitOptions fo;
    fo.differences = options.differences;
    fo.max_iterations = options.max_iterations;
    fo.reweight = options.reweight;
    fo.subtract_model_variance = options.subtract_model_variance;
    fo.cancel = options.cancel;
    RenderFitSummary summary;
    if (options.residuals == RenderFitResiduals::pixels)
        summary.warnings.push_back(
            "per-pixel residuals are not verified: over 16 seeds their fitted parameters lay on "
            "average +9 of their stated uncertainties from the truth (docs/fitting.md, pixel "
            "mode); "
            "fit region means for uncertainties that hold");
    for (const RenderFitParameter& p : options.parameters) {
        const double current =
            current_value(microfacet_of(scene, p.material), p.material, p.parameter);
        const double initial = p.initial.value_or(current);
        const std::string name = fmt::format("{}.{}", p.material, parameter_name(p.parameter));
        for (const std::string& earlier : fo.names)
            if (earlier == name)
                fail("fit through the renderer: parameter {} is listed twice", name);
        fo.names.push_back(name);
        fo.initial.push_back(initial);
        fo.lower.push_back(p.lower);
        fo.upper.push_back(p.upper);
        fo.steps.push_back(p.step.value_or(default_step(initial, p.lower, p.upper)));
        summary.parameters.push_back({p.material, std::string(parameter_name(p.parameter)), initial,
                                      0.0, 0.0, p.lower, p.upper, fo.steps.back()});
    }

    std::vector<double> measured, measured_variance;
    for (const RenderFitView& v : views)
        append_values(v.measured, v, options, kMeasuredStd, measured, measured_variance);
    std::vector<double> measured_sigma(measured_variance.size());
    std::transform(measured_variance.begin(), measured_variance.end(), measured_sigma.begin(),
                   [](double v) { return std::sqrt(v); });

    simulation::Scene candidate = scene;
    if (options.samples_per_pixel > 0)
        candidate.sampling.samples_per_pixel = options.samples_per_pixel;
    candidate.sampling.seed = options.seed.value_or(scene.sampling.seed);
    // The one place the render's variance is made fit for weighting. The fit weighs each residual
    // by the render's variance as if it were known: a region's sum of two-replicate variances is
    // unbiased but, over a few dozen pixels with heavy-tailed glossy paths, has few effective
    // degrees of freedom, and the inverse of such an estimate weighs too much (χ²/dof 1.19–1.23
    // and n's pulls spread 1.6 over 16 seeds at two replicates). So the renders draw at least 16
    // replicates (min(R, spp): 8 at 8 spp), and residuals per pixel take the region's mean render
    // variance (kRenderVariance), not each pixel's own: with R − 1 dof one pixel's inverse is
    // R − 1 over R − 3 of the true one on average (7/5 at 8 spp), and the heavy-tailed glossy
    // pixels whose spread came out small would weigh most. The region's mean has n·(R − 1) dof.
    candidate.sampling.replicates =
        std::max(candidate.sampling.replicates, simulation::kPerPixelReplicates);
    std::map<std::string, std::size_t> fitted_materials;  // name → scene material index
    for (const RenderFitParameter& p : options.parameters)
        fitted_materials[p.material] = material_index(scene, p.material);

    // Only the regions' pixels are traced: a pixel's value does not depend on which others are
    // rendered.
    std::vector<std::vector<std::uint8_t>> masks;
    for (const RenderFitView& v : views) {
        masks.emplace_back(static_cast<std::size_t>(v.camera.width()) *
                               static_cast<std::size_t>(v.camera.height()),
                           0);
        for (const RenderFitRegion& r : v.regions)
            for (std::size_t i : r.pixels) masks.back()[i] = 1;
    }

    int renders = 0;
    // An upper bound for the bar: every solve's iterations, each with its finite differences.
    const int per_point = 1 + static_cast<int>(fo.initial.size()) *
                                  (options.differences == FiniteDifference::central ? 2 : 1);
    const std::size_t bar_total =
        static_cast<std::size_t>((options.reweight ? 2 : 1) * (options.max_iterations + 2) *
                                 per_point * static_cast<int>(views.size()));
    std::unique_ptr<ProgressReporter> bar;
    if (options.show_progress)
        bar = std::make_unique<ProgressReporter>("fit through the renderer (renders)", bar_total);

    const NoisyModel model = [&](const std::vector<double>& theta) {
        for (const auto& [material, index] : fitted_materials) {
            std::vector<std::pair<MicrofacetParameter, double>> values;
            for (std::size_t i = 0; i < options.parameters.size(); ++i)
                if (options.parameters[i].material == material)
                    values.emplace_back(options.parameters[i].parameter, theta[i]);
            candidate.materials[index].brdf = microfacet_with(scene, material, values);
        }
        simulation::RenderOptions ro;
        ro.threads = options.threads;
        ro.cancel = options.cancel;
        // The first render loads the unchanged materials' tables (disk cache); later ones keep the
        // candidates' tables in memory only.
        if (renders > 0)
            ro.emissivity_cache_dir = std::filesystem::path();
        else
            ro.emissivity_cache_dir = options.emissivity_cache_dir;
        NoisyPrediction prediction;
        for (std::size_t v = 0; v < views.size(); ++v) {
            candidate.camera = views[v].camera;
            ro.pixel_mask = &masks[v];
            const Image rendered = simulation::render(candidate, ro);
            ++renders;
            if (bar) bar->advance();
            append_values(rendered, views[v], options, kRenderVariance, prediction.value,
                          prediction.variance);
        }
        return prediction;
    };

    const NoisyModelFitResult fit = fit_noisy_model(model, measured, measured_sigma, fo);
    if (bar) bar->finish();

    for (std::size_t i = 0; i < summary.parameters.size(); ++i) {
        summary.parameters[i].value = fit.values[i];
        summary.parameters[i].std_uncertainty = fit.std_uncertainty[i];
        if (!fit.model_variance_shift.empty())
            summary.parameters[i].variance_shift = fit.model_variance_shift[i];
    }
    summary.covariance = fit.covariance;
    summary.correlation = fit.correlation;
    summary.covariance_available = fit.covariance_available;
    summary.chi2 = fit.chi2;
    summary.dof = fit.dof;
    summary.reduced_chi2 = fit.reduced_chi2;
    summary.usable = fit.usable;
    summary.termination = fit.termination;
    summary.solver_report = fit.solver_report;
    summary.iterations = fit.iterations;
    summary.renders = renders;
    summary.warnings = fit.warnings;
    std::size_t j = 0;
    for (std::size_t v = 0; v < views.size(); ++v)
        for (std::size_t r = 0; r < views[v].regions.size(); ++r)
            for (int k : options.stokes) {
                const auto one = [&](std::size_t pixel) {
                    summary.comparisons.push_back(
                        {v, r, k, pixel, measured[j], fit.model[j], measured_sigma[j],
                         std::sqrt(fit.model_variance[j]), fit.normalized_residuals[j]});
                    ++j;
                };
                if (options.residuals == RenderFitResiduals::pixels)
                    for (std::size_t i : views[v].regions[r].pixels) one(i);
                else
                    one(0);
            }
    summary.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return summary;
}

std::string RenderFitSummary::FullReport() const {
    std::string out = "fit through the renderer\n";
    for (const auto& p : parameters)
        out += fmt::format(
            "  {}.{:<10} {:.5f} ± {:.5f}  (start {:.5f}, bounds [{}, {}], step {:.4g}; render "
            "variance's pull {:+.2g})\n",
            p.material, p.name, p.value, p.std_uncertainty, p.initial, p.lower, p.upper, p.step,
            p.variance_shift);
    out += fmt::format("  chi2 {:.3f} for {} dof: chi2/dof {:.3f}\n", chi2, dof, reduced_chi2);
    if (parameters.size() > 1 && covariance_available) {
        out += "  correlation:";
        for (Eigen::Index i = 0; i < correlation.rows(); ++i)
            for (Eigen::Index k = i + 1; k < correlation.cols(); ++k)
                out += fmt::format(" {}.{}~{}.{} {:+.3f}",
                                   parameters[static_cast<std::size_t>(i)].material,
                                   parameters[static_cast<std::size_t>(i)].name,
                                   parameters[static_cast<std::size_t>(k)].material,
                                   parameters[static_cast<std::size_t>(k)].name, correlation(i, k));
        out += "\n";
    }
    out += fmt::format("  {} renders, {} iterations, {:.1f} s; {}\n", renders, iterations, seconds,
                       termination);
    for (const auto& w : warnings) out += "  warning: " + w + "\n";
    return out;
}

}  // namespace tirpol::fitting
