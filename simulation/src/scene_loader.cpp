#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <tuple>

#include "csv_columns.h"
#include "material_resolution.h"
#include "scene_thermal.h"
#include "temperature_value.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/limits.h"
#include "tirpol/simulation/scene.h"

namespace tirpol::simulation {

namespace {

Vec3 vec3_of(const ConfigNode& node) {
    const auto v = node.as<std::vector<double>>();
    if (v.size() != 3) node.fail(fmt::format("expected 3 numbers [x, y, z], got {}", v.size()));
    return {v[0], v[1], v[2]};
}

Transform transform_of(const std::optional<ConfigNode>& node) {
    Transform t;
    if (!node) return t;
    node->check_keys({"translate", "rotate_deg", "scale"});
    if (auto n = node->find("translate")) t.translate = vec3_of(*n);
    if (auto n = node->find("rotate_deg"))
        t.rotation = Transform::rotation_from_euler_deg(vec3_of(*n));
    if (auto n = node->find("scale")) {
        t.scale = n->is_sequence() ? vec3_of(*n) : Vec3::Constant(n->as<double>());
        if (t.scale.cwiseAbs().minCoeff() <= 0.0) n->fail("scale factors must be non-zero");
    }
    return t;
}

int segments_of(const ConfigNode& g) {
    const double s = g.get_or("segments", 96.0);
    if (s < 3 || s > 100000 || s != std::floor(s))
        g.at("segments").fail("expected an integer number of segments ≥ 3");
    return static_cast<int>(s);
}

/// What add_geometry tells the rest of the loader about an object's geometry.
struct AddedGeometry {
    bool is_sphere = false;
    /// Vertex positions in the file's or primitive's own frame, before any transform (per-vertex
    /// data files refer to them).
    std::vector<Vec3> object_positions;
    std::filesystem::path mesh_file;               ///< empty for primitives
    std::vector<std::string> material_names;       ///< a mesh file's, read_mesh_file()
    std::vector<std::uint32_t> triangle_material;  ///< index into material_names
};

/// Adds the object's geometry to the tracer.
AddedGeometry add_geometry(const ConfigNode& g, const Transform& t, RayTracer& tracer) {
    const std::string type = g.get<std::string>("type");
    AddedGeometry added;
    TriangleMesh mesh;
    if (type == "sphere") {
        g.check_keys({"type", "radius"});
        if (!t.uniform_scale())
            g.fail("a sphere needs a uniform scale (use a mesh for ellipsoids)");
        tracer.add_sphere(t.translate, g.get_in_range("radius", 1e-9, 1e9) * std::abs(t.scale.x()));
        added.is_sphere = true;
        return added;
    }
    if (type == "mesh") {
        g.check_keys({"type", "file", "up_axis"});
        const ConfigNode file = g.at("file");
        const auto path = g.resolve_path(file.as<std::string>());
        if (!std::filesystem::is_regular_file(path))
            file.fail("mesh file not found: " + path.string());
        UpAxis up = default_up_axis(path);
        if (auto n = g.find("up_axis")) {
            const auto name = n->as<std::string>();
            const auto axis = up_axis_from_name(name);
            if (!axis)
                n->fail(fmt::format("expected y or z (the file's axis that points up), got \"{}\"",
                                    name));
            up = *axis;
        }
        MeshFile read = read_mesh_file(path);
        added.mesh_file = path;
        added.material_names = std::move(read.material_names);
        added.triangle_material = std::move(read.triangle_material);
        added.object_positions = read.mesh.positions;
        // The file's axes to the z-up world first; the object's transform then acts in the world.
        Transform to_world;
        to_world.rotation = z_up_rotation(up);
        transform_mesh(read.mesh, to_world);
        transform_mesh(read.mesh, t);
        tracer.add_mesh(std::move(read.mesh));
        return added;
    } else if (type == "box") {
        g.check_keys({"type", "size"});
        const Vec3 size = vec3_of(g.at("size"));
        if (size.minCoeff() <= 0.0) g.at("size").fail("box edge lengths must be positive");
        mesh = make_box(size);
    } else if (type == "plane") {
        g.check_keys({"type", "size"});
        const auto s = g.get<std::vector<double>>("size");
        if (s.size() != 2 || s[0] <= 0.0 || s[1] <= 0.0)
            g.at("size").fail("expected [size_x, size_y], positive");
        mesh = make_plane(s[0], s[1]);
    } else if (type == "disk") {
        g.check_keys({"type", "radius", "segments"});
        mesh = make_disk(g.get_in_range("radius", 1e-9, 1e9), segments_of(g));
    } else if (type == "cylinder") {
        g.check_keys({"type", "radius", "height", "segments", "caps"});
        mesh =
            make_cylinder(g.get_in_range("radius", 1e-9, 1e9), g.get_in_range("height", 1e-9, 1e9),
                          segments_of(g), g.get_or("caps", true));
    } else {
        g.at("type").fail("unknown geometry type \"" + type +
                          "\" (expected mesh, sphere, box, plane, disk or cylinder)");
    }
    added.object_positions = mesh.positions;
    transform_mesh(mesh, t);
    tracer.add_mesh(std::move(mesh));
    return added;
}

/// Per-face materials: each material name the mesh file uses, mapped by the object's `materials:`
/// to a library name (or a material file, or an inline material). Every name the file uses must be
/// mapped and every mapped name must be in the file; either miss is an error naming the material
/// and the file.
std::vector<std::uint32_t> triangle_materials_of(const ConfigNode& mapping,
                                                 const AddedGeometry& geometry,
                                                 detail::MaterialResolver& resolver,
                                                 std::vector<SceneMaterial>& materials) {
    if (geometry.mesh_file.empty())
        mapping.fail(
            "per-face materials need a mesh file (geometry type mesh); give `material` for a "
            "primitive");
    if (!mapping.is_map())
        mapping.fail(
            "expected a mapping from the mesh file's material names to material library names, "
            "e.g. {Paint: glossy_black_paint, Glass: silica_glass}");
    const std::string file = geometry.mesh_file.string();
    const auto mapped = mapping.keys();
    for (const auto& name : geometry.material_names) {
        if (name.empty())
            mapping.fail(fmt::format(
                "mesh file {} has faces whose material has no name (a glTF material without "
                "`name`, or a primitive without `material`): name it in the file to map it",
                file));
        if (std::find(mapped.begin(), mapped.end(), name) == mapped.end())
            mapping.fail(fmt::format(
                "mesh file {} uses material \"{}\"{}, which this mapping does not name (it names: "
                "{})",
                file, name,
                name == kNoFileMaterial
                    ? " (faces the file gives no material: an OBJ without usemtl before them, "
                      "or a glTF primitive without material)"
                    : "",
                fmt::join(mapped, ", ")));
    }
    for (const auto& name : mapped)
        if (std::find(geometry.material_names.begin(), geometry.material_names.end(), name) ==
            geometry.material_names.end())
            mapping.at(name).fail(
                fmt::format("mesh file {} has no material \"{}\" (its materials: {})", file, name,
                            fmt::join(geometry.material_names, ", ")));
    std::vector<std::uint32_t> scene_index;
    for (const auto& name : geometry.material_names)
        scene_index.push_back(resolver.resolve(mapping.at(name), materials));
    std::vector<std::uint32_t> out;
    out.reserve(geometry.triangle_material.size());
    for (const std::uint32_t m : geometry.triangle_material) out.push_back(scene_index[m]);
    return out;
}

bool in_temperature_range(double t_k) {
    return t_k >= limits::kMinTemperatureK && t_k <= limits::kMaxTemperatureK;
}

/// Per-vertex temperatures from a CSV of points (x, y, z in the mesh file's units, temperature_k):
/// each vertex takes the value of the point at its position, so the file does not depend on how a
/// mesh loader orders or duplicates vertices (OBJ faces, for one, are expanded per corner).
std::vector<double> vertex_temperatures(const ConfigNode& node, const std::filesystem::path& path,
                                        const std::vector<Vec3>& positions) {
    const auto cols = read_csv_columns(path, {"x", "y", "z", "temperature_k"});
    double extent = 0.0;
    for (const auto& p : positions) extent = std::max(extent, p.cwiseAbs().maxCoeff());
    const double cell = 1e-6 * std::max(extent, 1.0);
    using Key = std::tuple<long long, long long, long long>;
    const auto key = [&](const Vec3& p) {
        return Key{std::llround(p.x() / cell), std::llround(p.y() / cell),
                   std::llround(p.z() / cell)};
    };
    std::map<Key, double> points;
    for (std::size_t i = 0; i < cols[0].size(); ++i) {
        if (!in_temperature_range(cols[3][i]))
            node.fail(
                fmt::format("{}: row {}: temperature {} K is outside the physical range [{}, {}] K",
                            path.string(), i + 1, cols[3][i], limits::kMinTemperatureK,
                            limits::kMaxTemperatureK));
        points[key(Vec3(cols[0][i], cols[1][i], cols[2][i]))] = cols[3][i];
    }
    std::vector<double> out;
    for (std::size_t v = 0; v < positions.size(); ++v) {
        const auto [kx, ky, kz] = key(positions[v]);
        std::optional<double> found;
        for (long long dx = -1; dx <= 1 && !found; ++dx)
            for (long long dy = -1; dy <= 1 && !found; ++dy)
                for (long long dz = -1; dz <= 1 && !found; ++dz)
                    if (auto it = points.find(Key{kx + dx, ky + dy, kz + dz}); it != points.end())
                        found = it->second;
        if (!found)
            node.fail(fmt::format("{} has no temperature for mesh vertex {} at ({}, {}, {})",
                                  path.string(), v, positions[v].x(), positions[v].y(),
                                  positions[v].z()));
        out.push_back(*found);
    }
    return out;
}

TemperatureField temperature_of(const ConfigNode& node, bool is_sphere,
                                const std::vector<Vec3>& object_positions, bool has_weather) {
    if (is_predicted_temperature(node)) {
        if (!has_weather)
            node.fail(
                "\"predicted\" temperatures need the thermal solver's inputs: a `weather` entry "
                "and a `time` in the scene");
        return TemperatureField::constant(
            0.0);  // filled in by apply_scene_thermal once the geometry exists
    }
    if (node.is_scalar()) return TemperatureField::constant(temperature_k_from_config(node));
    if (!node.is_map())
        node.fail(
            "expected a temperature value, {vertex_csv: FILE} or {texture: FILE.exr, channel: "
            "NAME}");
    node.check_keys({"vertex_csv", "texture", "channel"});
    if (node.has("vertex_csv") == node.has("texture"))
        node.fail("give exactly one of vertex_csv or texture");
    if (node.has("vertex_csv")) {
        if (is_sphere)
            node.fail(
                "per-vertex temperatures need a triangle mesh (an analytic sphere has no "
                "vertices)");
        const auto path = node.resolve_path(node.get<std::string>("vertex_csv"));
        if (!std::filesystem::is_regular_file(path))
            node.at("vertex_csv").fail("file not found: " + path.string());
        return TemperatureField::per_vertex(
            vertex_temperatures(node.at("vertex_csv"), path, object_positions));
    }
    const auto path = node.resolve_path(node.get<std::string>("texture"));
    if (!std::filesystem::is_regular_file(path))
        node.at("texture").fail("file not found: " + path.string());
    const Image map = read_exr(path);
    const std::string channel = node.get_or<std::string>("channel", "temperature_k");
    if (!map.has_channel(channel))
        node.fail(fmt::format("{} has no channel '{}'", path.string(), channel));
    for (float v : map.channel(channel))
        if (!in_temperature_range(v))
            node.at("texture").fail(
                fmt::format("{}: temperature {} K is outside the physical range [{}, {}] K",
                            path.string(), v, limits::kMinTemperatureK, limits::kMaxTemperatureK));
    return TemperatureField::texture(map.channel(channel), map.width(), map.height());
}

}  // namespace

std::string max_bounces_problem(int max_bounces) {
    if (max_bounces >= 0 && max_bounces <= kMaxBouncesLimit) return {};
    return fmt::format(
        "expected 0–{} reflections (a safety cap: paths end by Russian roulette), got {}",
        kMaxBouncesLimit, max_bounces);
}

std::string_view estimator_name(Estimator estimator) {
    return estimator == Estimator::plain ? "plain" : "control-variate";
}

std::optional<Estimator> estimator_from_name(std::string_view name) {
    for (const Estimator e : {Estimator::plain, Estimator::control_variate})
        if (name == estimator_name(e)) return e;
    return std::nullopt;
}

int replicate_count(const SamplingSettings& sampling) {
    return std::max(1, std::min(sampling.replicates, sampling.samples_per_pixel));
}

int rendered_samples_per_pixel(const SamplingSettings& sampling) {
    const int r = replicate_count(sampling);
    return (sampling.samples_per_pixel + r - 1) / r * r;
}

namespace {

SamplingSettings sampling_of(const std::optional<ConfigNode>& node) {
    SamplingSettings s;
    if (!node) return s;
    node->check_keys({"spp", "max_bounces", "seed", "estimator", "replicates"});
    s.samples_per_pixel = node->get_or("spp", s.samples_per_pixel);
    if (s.samples_per_pixel < 1 || s.samples_per_pixel > limits::kMaxSamplesPerPixel)
        node->at("spp").fail(fmt::format("expected 1 to {} samples per pixel (limits.h)",
                                         limits::kMaxSamplesPerPixel));
    s.max_bounces = node->get_or("max_bounces", s.max_bounces);
    if (const std::string problem = max_bounces_problem(s.max_bounces); !problem.empty())
        node->at("max_bounces").fail(problem);
    const int seed = node->get_or("seed", 1);
    if (seed < 0) node->at("seed").fail("expected a non-negative seed");
    s.seed = static_cast<std::uint64_t>(seed);
    if (node->has("estimator")) {
        const auto name = node->at("estimator").as<std::string>();
        const auto estimator = estimator_from_name(name);
        if (!estimator)
            node->at("estimator")
                .fail(fmt::format("expected plain or control-variate, got '{}'", name));
        s.estimator = *estimator;
    }
    s.replicates = node->get_or("replicates", s.replicates);
    if (s.replicates < 1 || s.replicates > kMaxReplicates)
        node->at("replicates")
            .fail(fmt::format(
                "expected 1–{} independent replicates per pixel (their spread is the variance "
                "estimate, with replicates − 1 degrees of freedom; 1: no variance), got {}",
                kMaxReplicates, s.replicates));
    return s;
}

Band band_of(const ConfigNode& node) {
    node.check_keys({"lo_um", "hi_um", "rsr"});
    const double lo = node.get_in_range("lo_um", 0.1, 1000.0);
    const double hi = node.get_in_range("hi_um", 0.1, 1000.0);
    if (!(hi > lo)) node.at("hi_um").fail(fmt::format("hi_um ({}) must exceed lo_um ({})", hi, lo));
    std::optional<SpectralResponse> rsr;
    if (auto r = node.find("rsr")) {
        const auto path = r->resolve_path(r->as<std::string>());
        if (!std::filesystem::is_regular_file(path))
            r->fail("RSR file not found: " + path.string());
        rsr = SpectralResponse::load_csv(path);
    }
    return Band(lo, hi, rsr);
}

}  // namespace

Scene load_scene(const std::filesystem::path& path) {
    return load_scene(ConfigNode::load_file(path));
}

Scene load_scene(const ConfigNode& root) {
    std::vector<std::string> keys = {"band", "sampling",      "camera", "sky",
                                     "sun",  "materials_dir", "objects"};
    keys.insert(keys.end(), std::begin(kThermalSceneKeys), std::end(kThermalSceneKeys));
    root.check_keys(keys);
    const bool has_weather = root.has("weather");
    Band band = band_of(root.at("band"));
    PinholeCamera camera = PinholeCamera::from_config(root.at("camera"));
    // With a `weather` entry and no `sky`, apply_scene_thermal sets the sky from the weather.
    Sky sky = has_weather && !root.has("sky") ? Sky::uniform(1.0)
                                              : Sky::from_config(root.at("sky"), band);
    std::optional<Sun> sun;
    if (auto s = root.find("sun")) sun = Sun::from_config(*s, band);

    std::filesystem::path materials_dir = root.resolve_path("../materials");
    if (auto d = root.find("materials_dir")) {
        materials_dir = d->resolve_path(d->as<std::string>());
        if (!std::filesystem::is_directory(materials_dir))
            d->fail("materials directory not found: " + materials_dir.string());
    }
    detail::MaterialResolver resolver(materials_dir);

    auto tracer = std::make_shared<RayTracer>();
    std::vector<SceneMaterial> materials;
    std::vector<SceneObject> objects;
    const ConfigNode objects_node = root.at("objects");
    const auto elements = objects_node.elements();
    if (elements.empty()) objects_node.fail("a scene needs at least one object");
    for (const ConfigNode& o : elements) {
        o.check_keys({"name", "geometry", "transform", "material", "materials", "temperature"});
        SceneObject obj;
        obj.name = o.get_or<std::string>("name", fmt::format("object{}", objects.size()));
        const AddedGeometry geometry =
            add_geometry(o.at("geometry"), transform_of(o.find("transform")), *tracer);
        if (o.has("material") && o.has("materials"))
            o.fail(
                "give either `material` (one for the whole object) or `materials` (the mesh "
                "file's material names mapped to library names), not both");
        if (auto mapping = o.find("materials")) {
            obj.triangle_materials = triangle_materials_of(*mapping, geometry, resolver, materials);
            obj.material = obj.triangle_materials.front();
            if (std::all_of(obj.triangle_materials.begin(), obj.triangle_materials.end(),
                            [&](std::uint32_t m) { return m == obj.material; }))
                obj.triangle_materials.clear();
            const ConfigNode t = o.at("temperature");
            if (!obj.triangle_materials.empty() && t.is_scalar() && is_predicted_temperature(t))
                t.fail(
                    "a mesh with several materials needs its thermal material named: "
                    "{predicted: NAME}");
        } else {
            obj.material = resolver.resolve(o.at("material"), materials);
        }
        obj.temperature = temperature_of(o.at("temperature"), geometry.is_sphere,
                                         geometry.object_positions, has_weather);
        objects.push_back(std::move(obj));
    }
    tracer->commit();
    Scene scene{std::filesystem::absolute(root.file()),
                camera,
                band,
                sky,
                sun,
                sampling_of(root.find("sampling")),
                std::move(materials),
                std::move(objects),
                std::move(tracer)};
    if (has_weather) apply_scene_thermal(root, scene);
    return scene;
}

}  // namespace tirpol::simulation
