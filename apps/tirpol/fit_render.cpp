// `tirpol fit-render`: micro-facet parameters fitted through the renderer to measured Stokes images
// (docs/fitting.md, "Fit through the renderer").

#include <memory>

#include "cli.h"
#include "common_options.h"
#include "tirpol/core/error.h"
#include "tirpol/fitting/render_fit.h"

namespace tirpol::cli {

namespace {

struct FitRenderArgs {
    fitting::RenderFitRunOptions options;
    std::string scene;
    bool pixels = false, forward = false, quiet = false;
};

void run_fit_render(FitRenderArgs& a) {
    auto& o = a.options;
    o.scene = a.scene;
    o.fit.residuals =
        a.pixels ? fitting::RenderFitResiduals::pixels : fitting::RenderFitResiduals::region_means;
    o.fit.differences =
        a.forward ? fitting::FiniteDifference::forward : fitting::FiniteDifference::central;
    o.fit.show_progress = !a.quiet;
    const fitting::RenderFitSummary s = fitting::run_render_fit(o);
    print_text(s.FullReport());
    if (!s.IsSolutionUsable())
        fail("the fit did not converge to a usable solution ({})", s.termination);
}

void register_fit_render(CLI::App& app) {
    auto args = std::make_shared<FitRenderArgs>();
    auto* cmd = app.add_subcommand(
        "fit-render",
        "Fit micro-facet parameters through the renderer to measured Stokes images of a scene");
    add_required_input(cmd, "scene", args->scene,
                       "Scene YAML: geometry, temperatures, sky, materials (docs/scene-format.md)");
    cmd->add_option("--view", args->options.views,
                    "Measured view: STOKES.exr (the scene's camera) or "
                    "STOKES.exr,CAMERA.yaml,POSE.yaml; repeat")
        ->required()
        ->expected(1)  // one view per --view: its commas join files, they do not list views
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    cmd->add_option("--region", args->options.objects,
                    "Scene object whose interior pixels are compared; repeat or comma list")
        ->required()
        ->delimiter(',');
    cmd->add_option("--free", args->options.free,
                    "Parameter to fit: MATERIAL.PARAMETER=LOWER:UPPER[:INITIAL] (n k sigma bias "
                    "tau_deg omega_deg rho_d rho_v); repeat")
        ->required();
    cmd->add_option("--spp", args->options.fit.samples_per_pixel,
                    "Samples per pixel of every render (0: the scene's)")
        ->capture_default_str();
    cmd->add_option("--seed", args->options.fit.seed,
                    "The one seed of every render (default: the scene's)");
    cmd->add_flag("--pixels", args->pixels,
                  "Compare every pixel instead of region means (not verified: its uncertainties do "
                  "not hold yet, docs/fitting.md)");
    cmd->add_flag("--forward", args->forward, "Forward differences (half the renders, O(h) error)");
    cmd->add_option("--max-iterations", args->options.fit.max_iterations, "Per solve")
        ->capture_default_str();
    cmd->add_option("-t,--threads", args->options.fit.threads, "Render threads (0: all cores)")
        ->capture_default_str();
    cmd->add_flag("-q,--quiet", args->quiet, "No progress bar");
    cmd->callback([args] { run_fit_render(*args); });
}

}  // namespace

TIRPOL_REGISTER_COMMAND(610, register_fit_render);

}  // namespace tirpol::cli
