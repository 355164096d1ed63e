// `tirpol render SCENE.yaml -o OUTDIR`: polarized thermal-infrared rendering of a scene file
// (docs/scene-format.md) into a Stokes EXR with quicklooks, and optionally the polarizer images of
// the sensor model (docs/simulation.md).

#include <cstdio>
#include <optional>

#include "cli.h"
#include "tirpol/core/config.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/simulation/render_output.h"
#include "tirpol/simulation/renderer.h"
#include "tirpol/simulation/scene.h"
#include "tirpol/simulation/sensor_model.h"

namespace tirpol::cli {

namespace {
struct RenderArgs {
    std::string scene;
    std::string out_dir;
    std::optional<int> spp, threads, width, height, max_bounces;
    std::optional<std::uint64_t> seed;
    std::string sensor, estimator;
    bool quiet = false;
    bool force = false;
};

void run_render(const RenderArgs& a) {
    simulation::Scene scene = simulation::load_scene(a.scene);
    if (a.width.has_value() != a.height.has_value())
        usage_error("--width/--height", "give both or neither");
    if (a.width) {
        if (*a.width < 1 || *a.height < 1)
            usage_error("--width/--height", "expected positive sizes, got {}x{}", *a.width,
                        *a.height);
        scene.camera = scene.camera.resized(*a.width, *a.height);
    }
    if (a.spp) {
        if (*a.spp < 1) usage_error("--spp", "expected at least 1, got {}", *a.spp);
        scene.sampling.samples_per_pixel = *a.spp;
    }
    if (a.max_bounces) {
        if (const std::string problem = simulation::max_bounces_problem(*a.max_bounces);
            !problem.empty())
            usage_error("--max-bounces", "{}", problem);
        scene.sampling.max_bounces = *a.max_bounces;
    }
    if (a.seed) scene.sampling.seed = *a.seed;
    if (!a.estimator.empty()) {
        const auto estimator = simulation::estimator_from_name(a.estimator);
        if (!estimator)
            usage_error("--estimator", "expected plain or control-variate, got '{}'", a.estimator);
        scene.sampling.estimator = *estimator;
    }
    const std::string stem = std::filesystem::path(a.scene).stem().string();
    OutputGuard()
        .input(a.scene, "SCENE")
        .input(a.sensor, "--sensor")
        .output_folder(a.out_dir, "--output", {stem + ".exr", stem + "_*.png", stem + "_pol*.exr"})
        .check(a.force);
    simulation::RenderOptions options;
    options.threads = a.threads.value_or(0);
    options.show_progress = !a.quiet;
    simulation::RenderStatistics stats;
    const Image image = simulation::render(scene, options, &stats);

    const auto written = simulation::write_render_outputs(a.out_dir, stem, image);
    if (!a.sensor.empty()) {
        const auto model = simulation::SensorModel::from_config(ConfigNode::load_file(a.sensor));
        for (const Image& frame : simulation::polarizer_images(image, model, scene.band)) {
            const double angle = std::get<double>(frame.attributes().at("polarizer_angle_deg"));
            const auto path =
                std::filesystem::path(a.out_dir) / fmt::format("{}_pol{:03.0f}.exr", stem, angle);
            write_exr(path, frame);
            std::printf("  %s\n", path.c_str());
        }
    }
    std::printf(
        "rendered %s: %d×%d, %d spp (%d replicates), %.2f s (%.2f s emissivity tables: %d built, "
        "%d from the cache), %.3g Mrays/s\n",
        a.scene.c_str(), image.width(), image.height(),
        simulation::rendered_samples_per_pixel(scene.sampling),
        simulation::replicate_count(scene.sampling), stats.seconds, stats.setup_seconds,
        stats.emissivity_tables_built,
        stats.emissivity_tables_from_disk + stats.emissivity_tables_from_memory,
        1e-6 * static_cast<double>(stats.scene_rays + stats.shadow_rays) /
            std::max(stats.seconds - stats.setup_seconds, 1e-9));
    for (const auto& p : written) std::printf("  %s\n", p.c_str());
}

void register_render(CLI::App& app) {
    auto args = std::make_shared<RenderArgs>();
    auto* cmd = app.add_subcommand(
        "render", "Render a scene file into a polarized (Stokes) thermal-infrared image");
    cmd->add_option("scene", args->scene, "Scene YAML (docs/scene-format.md)")
        ->required()
        ->check(CLI::ExistingFile);
    // -o/--output as in every subcommand; --out is the old spelling, kept hidden.
    auto* output = cmd->add_option("-o,--output", args->out_dir,
                                   "Output directory (EXR + PNG quicklooks) (required)");
    cmd->add_option("--out", args->out_dir)->group("")->excludes(output);
    cmd->add_option("--spp", args->spp, "Samples per pixel (overrides the scene's sampling.spp)");
    cmd->add_option("--threads", args->threads,
                    "Worker threads (default: all cores); the image does not depend on it");
    cmd->add_option("--seed", args->seed, "Random seed (overrides sampling.seed)");
    cmd->add_option("--width", args->width,
                    "Image width in pixels (with --height; intrinsics scale along)");
    cmd->add_option("--height", args->height, "Image height in pixels");
    cmd->add_option("--max-bounces", args->max_bounces,
                    "Safety cap on reflections per path, 0–100000 (overrides sampling.max_bounces; "
                    "paths end by Russian roulette)");
    cmd->add_option("--estimator", args->estimator,
                    "Reflection estimator: control-variate (default, lower noise) or plain "
                    "(overrides sampling.estimator)");
    cmd->add_option("--sensor", args->sensor,
                    "Sensor-model YAML: also write the polarizer images I(α)")
        ->check(CLI::ExistingFile);
    cmd->add_flag("-q,--quiet", args->quiet, "No progress bar");
    add_force_flag(cmd, args->force);
    cmd->callback([args] {
        if (args->out_dir.empty()) throw CLI::RequiredError("--output");
        run_render(*args);
    });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(300, register_render);

}  // namespace tirpol::cli
