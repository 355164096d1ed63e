// tirpol.simulation: scenes from a YAML file or a Python dict, overrides of camera and sampling,
// and the polarized path tracer returning a tirpol.Image. render() runs with the GIL released and
// stops on Ctrl-C (interruptible.h).
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "image_conversion.h"
#include "interruptible.h"
#include "python_config.h"
#include "tirpol/core/error.h"
#include "tirpol/simulation/renderer.h"
#include "tirpol/simulation/scene.h"

namespace py = pybind11;

namespace tirpol::python {

namespace {

using simulation::Scene;

/// A dict's stand-in file name: relative paths (meshes, materials_dir, the default ../materials)
/// resolve against `base_dir`, and messages say where the dict came from.
std::filesystem::path dict_source(const std::filesystem::path& base_dir, const char* what) {
    return std::filesystem::absolute(base_dir).lexically_normal() /
           fmt::format("<{} from a Python dict>", what);
}

void check_positive(const char* field, long long value) {
    if (value < 1) fail("scene: {} must be ≥ 1, got {}", field, value);
}

void bind_scene(py::module_& m) {
    py::class_<Scene>(
        m, "Scene",
        "A scene ready to render (docs/scene-format.md). Camera and sampling can be overridden "
        "before render().")
        .def_property_readonly(
            "file", [](const Scene& s) { return s.file; },
            "The scene file (or the dict's stand-in).")
        .def_property_readonly("width", [](const Scene& s) { return s.camera.width(); })
        .def_property_readonly("height", [](const Scene& s) { return s.camera.height(); })
        .def_property_readonly(
            "band_um",
            [](const Scene& s) { return py::make_tuple(s.band.lo_um(), s.band.hi_um()); })
        .def_property_readonly("object_names",
                               [](const Scene& s) {
                                   std::vector<std::string> names;
                                   for (const auto& o : s.objects) names.push_back(o.name);
                                   return names;
                               })
        .def_property(
            "spp", [](const Scene& s) { return s.sampling.samples_per_pixel; },
            [](Scene& s, int spp) {
                check_positive("spp", spp);
                s.sampling.samples_per_pixel = spp;
            },
            "Samples per pixel.")
        .def_property(
            "replicates", [](const Scene& s) { return s.sampling.replicates; },
            [](Scene& s, int replicates) {
                if (replicates < 1 || replicates > simulation::kMaxReplicates)
                    fail(
                        "scene: replicates: expected 1–{} independent replicates per pixel, got {}",
                        simulation::kMaxReplicates, replicates);
                s.sampling.replicates = replicates;
            },
            "Independent replicates per pixel, whose spread is S*_var (replicates − 1 degrees of "
            "freedom per pixel; the default 2 is meant to be pooled over regions, 16 gives "
            "standalone per-pixel error bars; 1: no variance).")
        .def_property(
            "seed", [](const Scene& s) { return s.sampling.seed; },
            [](Scene& s, std::uint64_t seed) { s.sampling.seed = seed; },
            "Random seed (renders are reproducible).")
        .def_property(
            "max_bounces", [](const Scene& s) { return s.sampling.max_bounces; },
            [](Scene& s, int bounces) {
                if (const auto problem = simulation::max_bounces_problem(bounces); !problem.empty())
                    fail("scene: max_bounces: {}", problem);
                s.sampling.max_bounces = bounces;
            },
            "Safety cap on reflections per path.")
        .def(
            "set_camera",
            [](Scene& s, const py::dict& camera, const std::filesystem::path& base_dir) {
                s.camera = simulation::PinholeCamera::from_config(
                    config_from_python(camera, dict_source(base_dir, "camera")));
            },
            py::arg("camera"), py::arg("base_dir") = std::filesystem::path("."),
            "Replaces the camera by one given as the scene file's `camera` mapping, e.g. "
            "{'resolution': [64, 48], "
            "'fov_deg': 22, 'position': [0, -3, 1], 'look_at': [0, 0, 0.3]}.")
        .def(
            "resize",
            [](Scene& s, int width, int height) {
                check_positive("width", width);
                check_positive("height", height);
                s.camera = s.camera.resized(width, height);
            },
            py::arg("width"), py::arg("height"),
            "Same view at another resolution (intrinsics scaled).")
        .def("__repr__", [](const Scene& s) {
            return fmt::format("<tirpol.simulation.Scene {} {}x{} spp={} objects={}>",
                               s.file.filename().string(), s.camera.width(), s.camera.height(),
                               s.sampling.samples_per_pixel, s.objects.size());
        });

    m.def(
        "load_scene",
        [](const std::filesystem::path& path) { return simulation::load_scene(path); },
        py::arg("path"),
        "Loads a YAML scene file. Raises tirpol.Error naming the file, line and field for any "
        "mistake.");
    m.def(
        "scene_from_dict",
        [](const py::dict& scene, const std::filesystem::path& base_dir) {
            return simulation::load_scene(
                config_from_python(scene, dict_source(base_dir, "scene")));
        },
        py::arg("scene"), py::arg("base_dir") = std::filesystem::path("."),
        "Loads a scene given as a dict with the keys of the YAML format (the same loader and "
        "checks). Relative "
        "paths, and the default material folder ../materials, resolve against base_dir.");
}

void bind_render(py::module_& m) {
    m.def(
        "render",
        [](const Scene& scene, int threads, int tile_size,
           std::optional<std::filesystem::path> emissivity_cache_dir) {
            if (threads < 0)
                fail("render: threads must be ≥ 0 (0 uses every core), got {}", threads);
            if (tile_size < 1) fail("render: tile_size must be ≥ 1 pixel, got {}", tile_size);
            simulation::RenderOptions options;
            options.threads = threads;
            options.tile_size = tile_size;
            options.emissivity_cache_dir = std::move(emissivity_cache_dir);
            Image image = run_interruptible([&](const std::atomic<bool>& cancel) {
                simulation::RenderOptions o = options;
                o.cancel = &cancel;
                return simulation::render(scene, o);
            });
            return to_python(std::move(image));
        },
        py::arg("scene"), py::arg("threads") = 0, py::arg("tile_size") = 16,
        py::arg("emissivity_cache_dir") = py::none(),
        "Renders the scene. Returns a tirpol.Image of float32 arrays (H, W): S0 S1 S2 S3 (camera "
        "frame: 0° along "
        "image +x, 90° toward the image top; band radiance W/(m²·sr)), DoLP, AoP (degrees), S0_var "
        "S1_var S2_var "
        "(variance of the pixel mean), depth, normal_x/y/z, view_zenith_deg, object_id, "
        "material_id, temperature_k; "
        "header attributes in .attributes. Releases the GIL; Ctrl-C stops it (KeyboardInterrupt).");
}

}  // namespace

void bind_simulation(py::module_& m) {
    bind_scene(m);
    bind_render(m);
    bind_sensor_model(m);
}

}  // namespace tirpol::python
