// The twin's fit of the target paint through the renderer.

#include "paint_render_fit.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "tirpol/fitting/render_fit.h"

namespace tirpol::twin {

namespace {

constexpr std::size_t kMinimumRegionPixels = 10;  ///< fewer: too few for a region mean to mean much

/// The measurement as the fit sees it: S*_std² += the truth render's S*_var.
Image measured_with_render_noise(const Image& measured, const Image& truth) {
    Image m = measured;
    for (const char* s : {"S0", "S1", "S2"}) {
        auto& sd = m.channel(std::string(s) + "_std");
        const auto& var = truth.channel(std::string(s) + "_var");
        for (std::size_t i = 0; i < sd.size(); ++i)
            if (std::isfinite(var[i]))
                sd[i] = static_cast<float>(std::sqrt(double(sd[i]) * sd[i] + var[i]));
    }
    return m;
}

}  // namespace

TwinRenderFit fit_paint_through_renderer(const PaintRenderFitInputs& in) {
    const simulation::Scene& scene = *in.scene;
    const std::string material = scene.materials[in.target_material].name;
    std::vector<fitting::RenderFitView> views;
    for (std::size_t v = 0; v < in.cameras.size(); ++v) {
        fitting::RenderFitView view{"view" + std::to_string(v),
                                    in.cameras[v],
                                    measured_with_render_noise((*in.measured)[v], (*in.truth)[v]),
                                    {}};
        // The target and every other object painted with it (panels_night's rack): more pixels and
        // view angles of the same paint.
        for (std::size_t o = 0; o < scene.objects.size(); ++o) {
            if (o != in.target_object && scene.objects[o].material != in.target_material) continue;
            auto region = fitting::object_region((*in.truth)[v], o, scene.objects[o].name);
            if (region.pixels.size() >= kMinimumRegionPixels)
                view.regions.push_back(std::move(region));
        }
        if (!view.regions.empty()) views.push_back(std::move(view));
    }
    fitting::RenderFitOptions o;
    constexpr double kNLower = 1.2, kNUpper = 2.5, kSigmaLower = 0.05, kSigmaUpper = 1.0;
    o.parameters = {{material,
                     fitting::MicrofacetParameter::n,
                     kNLower,
                     kNUpper,
                     std::clamp(in.initial_n, kNLower, kNUpper),
                     {}},
                    {material,
                     fitting::MicrofacetParameter::sigma,
                     kSigmaLower,
                     kSigmaUpper,
                     std::clamp(in.initial_sigma, kSigmaLower, kSigmaUpper),
                     {}}};
    o.seed = in.seed;
    o.threads = in.threads;
    o.samples_per_pixel = in.samples_per_pixel;
    const fitting::RenderFitSummary s = fitting::fit_through_renderer(scene, views, o);
    TwinRenderFit r;
    const double truth[] = {in.true_n, in.true_sigma};
    for (std::size_t i = 0; i < s.parameters.size(); ++i)
        r.parameters.push_back({s.parameters[i].name, truth[i], s.parameters[i].value,
                                s.parameters[i].std_uncertainty, false});
    r.reduced_chi2 = s.reduced_chi2;
    r.dof = s.dof;
    r.renders = s.renders;
    r.usable = s.usable;
    r.warnings = s.warnings;
    return r;
}

}  // namespace tirpol::twin
