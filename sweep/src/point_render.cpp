#include "point_render.h"

#include <unistd.h>

#include <chrono>

#include "records_json.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/simulation/render_output.h"
#include "tirpol/simulation/renderer.h"
#include "tirpol/simulation/scene.h"
#include "tirpol/simulation/sensor_model.h"

namespace tirpol::sweep::detail {

namespace {

std::filesystem::path point_dir(const std::filesystem::path& out_dir, const SweepPoint& point) {
    return out_dir / "points" / point.id;
}

void write_point(const SweepSpec& spec, const SweepPoint& point, const std::filesystem::path& dir,
                 int threads, PointRecord& record) {
    const PointConfig config = point_config(spec, point);
    simulation::Scene scene = simulation::load_scene(config.scene);
    scene.sampling.seed = point.seed;
    simulation::RenderOptions options;
    options.threads = threads;
    simulation::RenderStatistics stats;
    const Image image = simulation::render(scene, options, &stats);
    record.render_seconds = stats.seconds;
    simulation::write_render_outputs(dir, "stokes", image);
    if (config.sensor) {
        simulation::SensorModel model = simulation::SensorModel::from_config(*config.sensor);
        model.seed = point.seed;
        // One frame per analyzer angle, in the model's order.
        const std::vector<Image> frames = simulation::polarizer_images(image, model, scene.band);
        for (std::size_t i = 0; i < frames.size(); ++i)
            write_exr(dir / fmt::format("pol{:03.0f}.exr", model.analyzer.angles_deg[i]),
                      frames[i]);
    }
    std::vector<std::string> objects;
    for (const auto& o : scene.objects) objects.push_back(o.name);
    record.statistics = point_statistics(image, objects, spec);
    write_file_atomic(dir / "statistics.json", statistics_json(*record.statistics).dump(2) + "\n");
}

}  // namespace

PointRecord render_point(const SweepSpec& spec, const SweepPoint& point,
                         const std::filesystem::path& out_dir, int threads) {
    PointRecord record;
    record.point = point;
    const auto start = std::chrono::steady_clock::now();
    const auto final_dir = point_dir(out_dir, point);
    // Unique per process: two ranks never share a temporary folder.
    const auto temp_dir = out_dir / "points" / fmt::format(".{}.partial-{}", point.id, ::getpid());
    std::error_code ignored;
    try {
        std::filesystem::remove_all(temp_dir);
        write_point(spec, point, temp_dir, threads, record);
        std::error_code ec;
        std::filesystem::rename(temp_dir, final_dir, ec);
        if (ec) {
            // Another run finished the same point first (rename does not replace a non-empty
            // folder).
            if (!std::filesystem::is_regular_file(final_dir / "statistics.json"))
                fail("cannot move {} to {}: {}", temp_dir.string(), final_dir.string(),
                     ec.message());
            std::filesystem::remove_all(temp_dir, ignored);
        }
        record.status = "rendered";
    } catch (const std::exception& e) {
        record.status = "failed";
        record.error = e.what();
        record.statistics.reset();
        std::filesystem::remove_all(temp_dir, ignored);
    }
    record.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return record;
}

std::optional<PointStatistics> finished_point(const std::filesystem::path& out_dir,
                                              const SweepPoint& point) {
    const auto file = point_dir(out_dir, point) / "statistics.json";
    if (!std::filesystem::is_regular_file(file)) return std::nullopt;
    const std::string text = read_file(file);
    const auto j = nlohmann::json::parse(text, nullptr, false);
    if (j.is_discarded())
        fail("{}: not valid JSON (delete the point's folder to render it again)", file.string());
    return statistics_from_json(j, file.string());
}

}  // namespace tirpol::sweep::detail
