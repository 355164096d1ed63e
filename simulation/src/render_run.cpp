#include <fmt/format.h>

#include <algorithm>

#include "tirpol/core/config.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/output_guard.h"
#include "tirpol/simulation/render_output.h"
#include "tirpol/simulation/scene.h"
#include "tirpol/simulation/sensor_model.h"

namespace tirpol::simulation {

namespace {
template <typename... Args>
[[noreturn]] void refuse(const std::string& option, fmt::format_string<Args...> format,
                         Args&&... args) {
    throw OptionValueError(option, fmt::format(format, std::forward<Args>(args)...));
}

void apply_overrides(const RenderRunOptions& o, Scene& scene) {
    if (o.width.has_value() != o.height.has_value())
        refuse("--width/--height", "give both or neither");
    if (o.width) {
        if (*o.width < 1 || *o.height < 1)
            refuse("--width/--height", "expected positive sizes, got {}x{}", *o.width, *o.height);
        scene.camera = scene.camera.resized(*o.width, *o.height);
    }
    if (o.samples_per_pixel) {
        if (*o.samples_per_pixel < 1)
            refuse("--spp", "expected at least 1, got {}", *o.samples_per_pixel);
        scene.sampling.samples_per_pixel = *o.samples_per_pixel;
    }
    if (o.max_bounces) {
        if (const std::string problem = max_bounces_problem(*o.max_bounces); !problem.empty())
            refuse("--max-bounces", "{}", problem);
        scene.sampling.max_bounces = *o.max_bounces;
    }
    if (o.seed) scene.sampling.seed = *o.seed;
    if (!o.estimator.empty()) {
        const auto estimator = estimator_from_name(o.estimator);
        if (!estimator)
            refuse("--estimator", "expected plain or control-variate, got '{}'", o.estimator);
        scene.sampling.estimator = *estimator;
    }
}
}  // namespace

RenderRun run_render(const RenderRunOptions& o) {
    Scene scene = load_scene(o.scene);
    apply_overrides(o, scene);
    const std::string stem = o.scene.stem().string();
    OutputGuard()
        .input(o.scene, "SCENE")
        .input(o.sensor, "--sensor")
        .output_folder(o.output, "--output", {stem + ".exr", stem + "_*.png", stem + "_pol*.exr"})
        .check(o.force);
    RenderOptions options;
    options.threads = o.threads;
    options.show_progress = o.show_progress;
    RenderRun run;
    run.scene = o.scene;
    const Image image = render(scene, options, &run.statistics);
    run.width = image.width();
    run.height = image.height();
    run.samples_per_pixel = rendered_samples_per_pixel(scene.sampling);
    run.replicates = replicate_count(scene.sampling);
    run.written = write_render_outputs(o.output, stem, image);
    if (o.sensor.empty()) return run;
    const auto model = SensorModel::from_config(ConfigNode::load_file(o.sensor));
    // One frame per analyzer angle, in the model's order.
    const std::vector<Image> frames = polarizer_images(image, model, scene.band);
    for (std::size_t i = 0; i < frames.size(); ++i) {
        run.polarizer_images.push_back(
            o.output / fmt::format("{}_pol{:03.0f}.exr", stem, model.analyzer.angles_deg[i]));
        write_exr(run.polarizer_images.back(), frames[i]);
    }
    return run;
}

std::string render_run_text(const RenderRun& r) {
    const RenderStatistics& s = r.statistics;
    std::string text;
    for (const auto& p : r.polarizer_images) text += fmt::format("  {}\n", p.string());
    text += fmt::format(
        "rendered {}: {}×{}, {} spp ({} replicates), {:.2f} s ({:.2f} s emissivity tables: {} "
        "built, {} from the cache), {:.3g} Mrays/s\n",
        r.scene.string(), r.width, r.height, r.samples_per_pixel, r.replicates, s.seconds,
        s.setup_seconds, s.emissivity_tables_built,
        s.emissivity_tables_from_disk + s.emissivity_tables_from_memory,
        1e-6 * static_cast<double>(s.scene_rays + s.shadow_rays) /
            std::max(s.seconds - s.setup_seconds, 1e-9));
    for (const auto& p : r.written) text += fmt::format("  {}\n", p.string());
    return text;
}

}  // namespace tirpol::simulation
