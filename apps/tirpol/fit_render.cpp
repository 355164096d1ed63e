// `tirpol fit-render`: micro-facet parameters fitted through the renderer to measured Stokes images
// (docs/fitting.md, "Fit through the renderer").

#include <cstdio>
#include <memory>

#include "cli.h"
#include "tirpol/core/error.h"
#include "tirpol/fitting/render_fit.h"
#include "tirpol/simulation/scene.h"

namespace tirpol::cli {

namespace {

struct FitRenderArgs {
    std::string scene;
    std::vector<std::string> views, objects, parameters;
    int spp = 0;
    std::uint64_t seed = 0;
    bool seed_set = false;
    bool pixels = false, forward = false, quiet = false;
    int max_iterations = 20;
    int threads = 0;
};

void run_fit_render(const FitRenderArgs& a) {
    const simulation::Scene scene = simulation::load_scene(a.scene);
    fitting::RenderFitOptions o;
    for (const std::string& p : a.parameters)
        o.parameters.push_back(
            parse_option_value("--free", [&] { return fitting::parse_render_fit_parameter(p); }));
    o.samples_per_pixel = a.spp;
    if (a.seed_set) o.seed = a.seed;
    o.residuals =
        a.pixels ? fitting::RenderFitResiduals::pixels : fitting::RenderFitResiduals::region_means;
    o.differences =
        a.forward ? fitting::FiniteDifference::forward : fitting::FiniteDifference::central;
    o.max_iterations = a.max_iterations;
    o.threads = a.threads;
    o.show_progress = !a.quiet;
    std::vector<fitting::RenderFitView> views;
    for (const std::string& v : a.views) {
        // MEASURED.exr or MEASURED.exr,CAMERA.yaml,POSE.yaml
        std::vector<std::string> parts;
        for (std::size_t from = 0;;) {
            const auto comma = v.find(',', from);
            parts.push_back(
                v.substr(from, comma == std::string::npos ? std::string::npos : comma - from));
            if (comma == std::string::npos) break;
            from = comma + 1;
        }
        if (parts.size() != 1 && parts.size() != 3)
            usage_error("--view", "{}: expected MEASURED.exr or MEASURED.exr,CAMERA.yaml,POSE.yaml",
                        v);
        views.push_back(
            fitting::load_render_fit_view(scene, parts[0], parts.size() == 3 ? parts[1] : "",
                                          parts.size() == 3 ? parts[2] : "", a.objects));
    }
    const fitting::RenderFitSummary s = fitting::fit_through_renderer(scene, views, o);
    std::printf("%s", s.FullReport().c_str());
    if (!s.IsSolutionUsable())
        fail("the fit did not converge to a usable solution ({})", s.termination);
}

void register_fit_render(CLI::App& app) {
    auto args = std::make_shared<FitRenderArgs>();
    auto* cmd = app.add_subcommand(
        "fit-render",
        "Fit micro-facet parameters through the renderer to measured Stokes images of a scene");
    cmd->add_option("scene", args->scene,
                    "Scene YAML: geometry, temperatures, sky, materials (docs/scene-format.md)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("--view", args->views,
                    "Measured view: STOKES.exr (the scene's camera) or "
                    "STOKES.exr,CAMERA.yaml,POSE.yaml; repeat")
        ->required();
    cmd->add_option("--region", args->objects,
                    "Scene object whose interior pixels are compared; repeat or comma list")
        ->required()
        ->delimiter(',');
    cmd->add_option("--free", args->parameters,
                    "Parameter to fit: MATERIAL.PARAMETER=LOWER:UPPER[:INITIAL] (n k sigma bias "
                    "tau_deg omega_deg "
                    "rho_d rho_v); repeat")
        ->required();
    cmd->add_option("--spp", args->spp, "Samples per pixel of every render (0: the scene's)")
        ->capture_default_str();
    cmd->add_option("--seed", args->seed, "The one seed of every render (default: the scene's)")
        ->each([args](const std::string&) { args->seed_set = true; });
    cmd->add_flag("--pixels", args->pixels, "Compare every pixel instead of region means");
    cmd->add_flag("--forward", args->forward, "Forward differences (half the renders, O(h) error)");
    cmd->add_option("--max-iterations", args->max_iterations, "Per solve")->capture_default_str();
    cmd->add_option("-t,--threads", args->threads, "Render threads (0: all cores)")
        ->capture_default_str();
    cmd->add_flag("-q,--quiet", args->quiet, "No progress bar");
    cmd->callback([args] { run_fit_render(*args); });
}

}  // namespace

TIRPOL_REGISTER_COMMAND(610, register_fit_render);

}  // namespace tirpol::cli
