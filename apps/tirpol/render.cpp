// `tirpol render SCENE.yaml -o OUTDIR`: polarized thermal-infrared rendering of a scene file
// (docs/scene-format.md) into a Stokes EXR with quicklooks, and optionally the polarizer images of
// the sensor model (docs/simulation.md).

#include <memory>

#include "cli.h"
#include "common_options.h"
#include "tirpol/simulation/render_output.h"

namespace tirpol::cli {

namespace {
struct RenderArgs {
    simulation::RenderRunOptions options;
    std::string scene, output, sensor;
    bool quiet = false;
};

void register_render(CLI::App& app) {
    auto args = std::make_shared<RenderArgs>();
    auto* cmd = app.add_subcommand(
        "render", "Render a scene file into a polarized (Stokes) thermal-infrared image");
    add_required_input(cmd, "scene", args->scene, "Scene YAML (docs/scene-format.md)");
    // -o/--output as in every subcommand; --out is the old spelling, kept hidden.
    auto* output = cmd->add_option("-o,--output", args->output,
                                   "Output directory (EXR + PNG quicklooks) (required)");
    cmd->add_option("--out", args->output)->group("")->excludes(output);
    cmd->add_option("--spp", args->options.samples_per_pixel,
                    "Samples per pixel (overrides the scene's sampling.spp)");
    cmd->add_option("--threads", args->options.threads,
                    "Worker threads (default: all cores); the image does not depend on it");
    cmd->add_option("--seed", args->options.seed, "Random seed (overrides sampling.seed)");
    cmd->add_option("--width", args->options.width,
                    "Image width in pixels (with --height; intrinsics scale along)");
    cmd->add_option("--height", args->options.height, "Image height in pixels");
    cmd->add_option("--max-bounces", args->options.max_bounces,
                    "Safety cap on reflections per path, 0–100000 (overrides sampling.max_bounces; "
                    "paths end by Russian roulette)");
    cmd->add_option("--estimator", args->options.estimator,
                    "Reflection estimator: control-variate (default, lower noise) or plain "
                    "(overrides sampling.estimator)");
    cmd->add_option("--sensor", args->sensor,
                    "Sensor-model YAML: also write the polarizer images I(α)")
        ->check(CLI::ExistingFile);
    cmd->add_flag("-q,--quiet", args->quiet, "No progress bar");
    add_force_flag(cmd, args->options.force);
    cmd->callback([args] {
        if (args->output.empty()) throw CLI::RequiredError("--output");
        auto& o = args->options;
        o.scene = args->scene;
        o.output = args->output;
        o.sensor = args->sensor;
        o.show_progress = !args->quiet;
        print_text(simulation::render_run_text(simulation::run_render(o)));
    });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(300, register_render);

}  // namespace tirpol::cli
