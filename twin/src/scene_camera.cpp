#include "tirpol/twin/scene_camera.h"

#include <fmt/format.h>

#include <cstdint>
#include <mutex>

#include "tirpol/acquisition/camera.h"
#include "tirpol/acquisition/device_uri.h"
#include "tirpol/acquisition/sim/simulated_camera.h"
#include "tirpol/core/error.h"
#include "tirpol/core/source_tree.h"
#include "tirpol/simulation/dofp_sensor.h"
#include "tirpol/simulation/renderer.h"
#include "tirpol/simulation/scene.h"
#include "tirpol/twin/instrument.h"

namespace tirpol::twin {

namespace fs = std::filesystem;

namespace {

bool is_scene_file(const std::string& target) {
    const std::string ext = fs::path(target).extension().string();
    return ext == ".yaml" || ext == ".yml";
}

fs::path resolve_scene_path(const acquisition::DeviceUri& u) {
    const fs::path path(u.target);
    if (path.is_absolute() || fs::exists(path)) return path;
    const auto first = path.begin();
    if (first != path.end() && *first == "config")
        return find_config(path.lexically_relative("config"));
    fail("device URI '{}': scene file '{}' not found (relative to {})", u.text, u.target,
         fs::current_path().string());
}

}  // namespace

std::unique_ptr<acquisition::Camera> open_scene_camera(const std::string& uri) {
    const acquisition::DeviceUri u = acquisition::parse_device_uri(uri);
    if (u.scheme != "sim" || !is_scene_file(u.target))
        fail("device URI '{}': expected sim://<scene.yaml>", uri);
    u.check_keys({"width", "height", "spp", "fps", "buffers", "microgrid", "seed"});
    simulation::Scene scene = simulation::load_scene(resolve_scene_path(u));
    const int width = u.integer("width", scene.camera.width()),
              height = u.integer("height", scene.camera.height());
    if (width < 1 || height < 1 || width > 8192 || height > 8192)
        fail("device URI '{}': width={} height={} (expected 1…8192 pixels each)", uri, width,
             height);
    scene.camera = scene.camera.resized(width, height);
    scene.sampling.samples_per_pixel = u.integer("spp", scene.sampling.samples_per_pixel);
    if (scene.sampling.samples_per_pixel < 1) fail("device URI '{}': spp must be ≥ 1", uri);

    acquisition::SimulatedCameraConfig config;
    std::shared_ptr<TwinWorld> world;
    if (const auto it = u.query.find("microgrid"); it != u.query.end()) {
        // A microgrid camera: the DoFP sensor stage (each pixel its own micro-polarizer and
        // bolometer, DofpSensorSpec's defaults, the array drawn from `seed`) at the scene's full
        // resolution, no polarizer in front.
        simulation::DofpSensorSpec spec;
        spec.pattern_deg = acquisition::parse_microgrid_pattern_deg(
            it->second, fmt::format("device URI '{}': microgrid", uri));
        const int seed = u.integer("seed", 1);
        if (seed < 0) fail("device URI '{}': seed={} (expected an integer ≥ 0)", uri, seed);
        spec.seed = static_cast<std::uint64_t>(seed);
        if (width % 2 != 0 || height % 2 != 0)
            fail("device URI '{}': width={} height={}; a microgrid camera needs even sizes", uri,
                 width, height);
        world = std::make_shared<TwinWorld>(simulation::DofpSensor(spec, width, height, scene.band),
                                            ReferencePolarizer{}, scene.band);
        config.microgrid_pattern_deg = spec.pattern_deg;
    } else {
        if (u.query.count("seed") != 0)
            fail("device URI '{}': seed is a microgrid camera's key (give microgrid= too)", uri);
        // The twin instrument's detector and grid, with the night air at the sky's clear-sky
        // temperature.
        world = std::make_shared<TwinWorld>(twin_sensor(scene.band, scene.sky.temperature_k(1.0)),
                                            scene.band, width, height);
    }
    world->set_scene(simulation::render(scene));

    config.name = fs::path(u.target).stem().string();
    config.width = width;
    config.height = height;
    config.frame_rate_hz = u.number("fps", config.frame_rate_hz);
    config.buffers = u.integer("buffers", config.buffers);
    return std::make_unique<acquisition::SimulatedCamera>(
        config,
        [world](double angle_deg, std::vector<float>& counts) { world->fill(angle_deg, counts); });
}

void register_twin_device_schemes() {
    static std::once_flag once;
    std::call_once(once, [] {
        // sim:// keeps its built-in targets (sim://uniform): the scene camera takes only scene
        // files.
        auto built_in = std::make_shared<acquisition::CameraFactory>();
        *built_in = acquisition::register_camera_scheme(
            "sim",
            [built_in](const std::string& uri)
                -> acquisition::Result<std::unique_ptr<acquisition::Camera>> {
                if (is_scene_file(acquisition::parse_device_uri(uri).target))
                    return std::unique_ptr<acquisition::Camera>(open_scene_camera(uri));
                return (*built_in)(uri);
            });
    });
}

}  // namespace tirpol::twin
