#include "scene_thermal.h"

#include <algorithm>
#include <cmath>

#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/thermal/civil_time.h"
#include "tirpol/thermal/solar_position.h"
#include "tirpol/thermal/thermal_config.h"

namespace tirpol::simulation {

namespace {

using thermal::FacetRequest;
using thermal::ThermalMaterial;

/// Solar constant, W/m² (Kopp & Lean 2011), for the sun's grey transmittance DNI / E₀.
constexpr double kSolarConstant = 1360.8;
/// Resolution of the (u, v) temperature map of an analytic sphere.
constexpr int kSphereMapWidth = 48, kSphereMapHeight = 24;

thermal::Facet facet_of(const Vec3& n) {
    thermal::Facet f;
    f.tilt_deg = rad_to_deg(std::acos(std::clamp(n.z(), -1.0, 1.0)));
    double az = rad_to_deg(std::atan2(n.x(), n.y()));
    f.azimuth_deg = az < 0.0 ? az + 360.0 : az;
    return f;
}

// Shadow of the direct sun at a surface point, by the scene's ray tracer (1 shadowed, 0 lit).
thermal::ShadowFunction shadow_at(const RayTracer& tracer, const Vec3& position,
                                  const Vec3& normal) {
    return [&tracer, p = Vec3(position + 1e-4 * normal)](double, const Vec3& sun) {
        return tracer.occluded(p, sun, 1e-6, 1e30) ? 1.0 : 0.0;
    };
}

const ThermalMaterial& thermal_material_for(const ConfigNode& node,
                                            const std::string& scene_material,
                                            const std::vector<ThermalMaterial>& materials) {
    const std::string name = node.is_scalar() ? scene_material : node.get<std::string>("predicted");
    for (const auto& m : materials)
        if (m.name == name) return m;
    std::vector<std::string> names;
    for (const auto& m : materials) names.push_back(m.name);
    const std::string hint = closest_match(name, names);
    node.fail("no thermal material '" + name + "' in `thermal_materials`" +
              (hint.empty() ? "" : "; did you mean '" + hint + "'?"));
}

struct Inputs {
    std::shared_ptr<const thermal::WeatherSeries> weather;
    double time_s = 0.0;
    thermal::ThermalOptions options;
    std::vector<ThermalMaterial> materials;
};

Inputs inputs_of(const ConfigNode& root) {
    Inputs in;
    std::optional<thermal::Site> site;
    if (auto n = root.find("site")) site = thermal::parse_site(*n);
    in.weather = thermal::load_weather(root.at("weather"), site);
    try {
        in.time_s = thermal::parse_time(root.get<std::string>("time"),
                                        in.weather->site().utc_offset_h, "time");
    } catch (const Error& e) {
        root.at("time").fail(e.what());
    }
    if (auto n = root.find("thermal")) in.options = thermal::parse_thermal_options(*n);
    if (auto n = root.find("thermal_materials"))
        for (const auto& m : n->elements())
            in.materials.push_back(thermal::parse_thermal_material(m));
    return in;
}

// The object's `transform` (translate, rotate_deg, scale), as the scene loader reads it.
Transform transform_of(const ConfigNode& object) {
    Transform t;
    const auto node = object.find("transform");
    if (!node) return t;
    const auto vec = [](const ConfigNode& n) {
        const auto v = n.as<std::vector<double>>();
        if (v.size() != 3) n.fail("expected 3 numbers");
        return Vec3(v[0], v[1], v[2]);
    };
    if (auto n = node->find("translate")) t.translate = vec(*n);
    if (auto n = node->find("rotate_deg")) t.rotation = Transform::rotation_from_euler_deg(vec(*n));
    if (auto n = node->find("scale"))
        t.scale = n->is_sequence() ? vec(*n) : Vec3::Constant(n->as<double>());
    return t;
}

}  // namespace

bool is_predicted_temperature(const ConfigNode& node) {
    if (node.is_scalar()) return node.as<std::string>() == "predicted";
    return node.is_map() && node.has("predicted");
}

void apply_scene_thermal(const ConfigNode& root, Scene& scene) {
    const Inputs inputs = inputs_of(root);
    const thermal::Site& where = inputs.weather->site();
    const double time_s = inputs.time_s;
    const thermal::ThermalOptions& options = inputs.options;
    const thermal::WeatherRecord record = inputs.weather->at(time_s);

    // One weather record drives the renderer's sky and sun and the solver's loads.
    if (!root.has("sky")) {
        const auto sky = thermal::sky_from_weather(record, where, options);
        scene.sky = Sky::clear_sky(sky.air_temperature_k(), sky.window_zenith_emissivity());
    }
    if (!root.has("sun")) {
        thermal::SpaInput in;
        in.unix_seconds = time_s;
        in.latitude_deg = where.latitude_deg;
        in.longitude_deg = where.longitude_deg;
        in.elevation_m = where.elevation_m;
        in.pressure_mbar = record.pressure_pa / 100.0;
        in.temperature_c = record.air_temperature_c;
        in.delta_t_s = options.delta_t_s;
        const thermal::SolarPosition sun = thermal::solar_position(in);
        scene.sun.reset();
        if (sun.zenith_deg < 90.0 && record.direct_normal_w_m2 > 0.0) {
            Sun s;
            s.direction = thermal::sun_direction(sun);
            const double e0 = kSolarConstant / (sun.earth_radius_au * sun.earth_radius_au);
            s.transmittance = std::clamp(record.direct_normal_w_m2 / e0, 0.0, 1.0);
            scene.sun = s;
        }
    }

    for (const PredictedTemperatures& p : predict_scene_temperatures(root, scene)) {
        SceneObject& obj = scene.objects[p.object];
        obj.temperature = p.map_k.empty() ? TemperatureField::per_vertex(p.vertex_k)
                                          : TemperatureField::texture(p.map_k, p.width, p.height);
    }
}

std::vector<PredictedTemperatures> predict_scene_temperatures(const ConfigNode& root,
                                                              const Scene& scene) {
    const Inputs in = inputs_of(root);
    std::vector<PredictedTemperatures> out;
    const auto objects = root.at("objects").elements();
    for (std::size_t i = 0; i < objects.size() && i < scene.objects.size(); ++i) {
        const ConfigNode node = objects[i].at("temperature");
        if (!is_predicted_temperature(node)) continue;
        const SceneObject& obj = scene.objects[i];
        const ThermalMaterial& material =
            thermal_material_for(node, scene.materials[obj.material].name, in.materials);
        const TriangleMesh& mesh = scene.tracer->mesh(static_cast<std::uint32_t>(i));
        std::vector<FacetRequest> requests;
        PredictedTemperatures p;
        p.object = i;
        if (!mesh.positions.empty()) {
            for (std::size_t v = 0; v < mesh.positions.size(); ++v)
                requests.push_back({&material, facet_of(mesh.normals[v]),
                                    shadow_at(*scene.tracer, mesh.positions[v], mesh.normals[v])});
            p.vertex_k =
                thermal::predict_surface_temperatures(*in.weather, requests, in.time_s, in.options);
            out.push_back(std::move(p));
            continue;
        }
        // Analytic sphere: centre and radius as the scene loader placed it (translate, uniform
        // scale).
        const ConfigNode o = objects[i];
        const Transform t = transform_of(o);
        const Vec3 centre = t.translate;
        const double radius = o.at("geometry").get<double>("radius") * std::abs(t.scale.x());
        // Texel (u, v) ↔ outward normal, the inverse of the ray tracer's sphere mapping
        // u = ½ + atan2(n_y, n_x)/2π, v = acos(n_z)/π.
        for (int row = 0; row < kSphereMapHeight; ++row) {
            for (int col = 0; col < kSphereMapWidth; ++col) {
                const double u = (col + 0.5) / kSphereMapWidth, v = (row + 0.5) / kSphereMapHeight;
                const double phi = 2.0 * kPi * (u - 0.5), theta = kPi * v;
                const Vec3 n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                             std::cos(theta));
                requests.push_back(
                    {&material, facet_of(n), shadow_at(*scene.tracer, centre + radius * n, n)});
            }
        }
        const auto temps =
            thermal::predict_surface_temperatures(*in.weather, requests, in.time_s, in.options);
        p.map_k.assign(temps.begin(), temps.end());
        p.width = kSphereMapWidth;
        p.height = kSphereMapHeight;
        out.push_back(std::move(p));
    }
    return out;
}

std::vector<std::filesystem::path> export_scene_temperatures(const ConfigNode& root,
                                                             const Scene& scene,
                                                             const std::filesystem::path& dir) {
    std::vector<std::filesystem::path> written;
    const auto objects = root.at("objects").elements();
    for (const PredictedTemperatures& p : predict_scene_temperatures(root, scene)) {
        const std::string& name = scene.objects[p.object].name;
        if (!p.map_k.empty()) {
            Image map(p.width, p.height);
            map.set_channel("temperature_k", p.map_k);
            write_stokes_image_header(map, {.units = "K"});
            const auto path = dir / (name + ".exr");
            write_exr(path, map);
            written.push_back(path);
            continue;
        }
        // Object coordinates: the inverse of x ↦ R·diag(s)·x + t.
        const Transform t = transform_of(objects[p.object]);
        const TriangleMesh& mesh = scene.tracer->mesh(static_cast<std::uint32_t>(p.object));
        std::string csv = "x,y,z,temperature_k\n";
        for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
            const Vec3 local =
                (t.rotation.transpose() * (mesh.positions[v] - t.translate)).cwiseQuotient(t.scale);
            csv += fmt::format("{:.9g},{:.9g},{:.9g},{:.6f}\n", local.x(), local.y(), local.z(),
                               p.vertex_k[v]);
        }
        const auto path = dir / (name + ".csv");
        write_file_atomic(path, csv);
        written.push_back(path);
    }
    return written;
}

}  // namespace tirpol::simulation
