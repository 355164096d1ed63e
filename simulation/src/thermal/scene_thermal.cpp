#include "tirpol/simulation/thermal/scene_thermal.h"

#include <algorithm>
#include <cmath>

#include "tirpol/core/error.h"
#include "tirpol/simulation/thermal/civil_time.h"
#include "tirpol/simulation/thermal/solar_position.h"
#include "tirpol/simulation/thermal/thermal_config.h"

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
thermal::ShadowFunction shadow_at(const RayTracer& tracer, const Vec3& position, const Vec3& normal) {
    return [&tracer, p = Vec3(position + 1e-4 * normal)](double, const Vec3& sun) {
        return tracer.occluded(p, sun, 1e-6, 1e30) ? 1.0 : 0.0;
    };
}

const ThermalMaterial& thermal_material_for(const ConfigNode& node, const std::string& scene_material,
                                            const std::vector<ThermalMaterial>& materials) {
    const std::string name = node.is_scalar() ? scene_material : node.get<std::string>("predicted");
    for (const auto& m : materials)
        if (m.name == name) return m;
    std::vector<std::string> names;
    for (const auto& m : materials) names.push_back(m.name);
    const std::string hint = closest_match(name, names);
    node.fail("no thermal material '" + name + "' in `thermal_materials`" + (hint.empty() ? "" : "; did you mean '" + hint + "'?"));
}

}  // namespace

bool is_predicted_temperature(const ConfigNode& node) {
    if (node.is_scalar()) return node.as<std::string>() == "predicted";
    return node.is_map() && node.has("predicted");
}

void apply_scene_thermal(const ConfigNode& root, Scene& scene) {
    std::optional<thermal::Site> site;
    if (auto n = root.find("site")) site = thermal::parse_site(*n);
    const auto weather = thermal::load_weather(root.at("weather"), site);
    const thermal::Site& where = weather->site();
    double time_s = 0.0;
    try {
        time_s = thermal::parse_time(root.get<std::string>("time"), where.utc_offset_h, "time");
    } catch (const Error& e) {
        root.at("time").fail(e.what());
    }
    const thermal::ThermalOptions options = root.has("thermal") ? thermal::parse_thermal_options(root.at("thermal")) : thermal::ThermalOptions{};
    std::vector<ThermalMaterial> materials;
    if (auto n = root.find("thermal_materials"))
        for (const auto& m : n->elements()) materials.push_back(thermal::parse_thermal_material(m));
    const thermal::WeatherRecord record = weather->at(time_s);

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

    const auto objects = root.at("objects").elements();
    for (std::size_t i = 0; i < objects.size() && i < scene.objects.size(); ++i) {
        const ConfigNode node = objects[i].at("temperature");
        if (!is_predicted_temperature(node)) continue;
        SceneObject& obj = scene.objects[i];
        const ThermalMaterial& material = thermal_material_for(node, scene.materials[obj.material].name, materials);
        const TriangleMesh& mesh = scene.tracer->mesh(static_cast<std::uint32_t>(i));
        std::vector<FacetRequest> requests;
        if (!mesh.positions.empty()) {
            for (std::size_t v = 0; v < mesh.positions.size(); ++v)
                requests.push_back({&material, facet_of(mesh.normals[v]), shadow_at(*scene.tracer, mesh.positions[v], mesh.normals[v])});
            obj.temperature = TemperatureField::per_vertex(thermal::predict_surface_temperatures(*weather, requests, time_s, options));
            continue;
        }
        // Analytic sphere: centre and radius as the scene loader placed it (translate, uniform scale).
        const ConfigNode o = objects[i];
        Vec3 centre = Vec3::Zero();
        double scale = 1.0;
        if (auto t = o.find("transform")) {
            if (auto tr = t->find("translate")) {
                const auto v = tr->as<std::vector<double>>();
                centre = {v[0], v[1], v[2]};
            }
            if (auto sc = t->find("scale")) scale = sc->is_sequence() ? sc->as<std::vector<double>>()[0] : sc->as<double>();
        }
        const double radius = o.at("geometry").get<double>("radius") * std::abs(scale);
        // Texel (u, v) ↔ outward normal, the inverse of the ray tracer's sphere mapping
        // u = ½ + atan2(n_y, n_x)/2π, v = acos(n_z)/π.
        for (int row = 0; row < kSphereMapHeight; ++row) {
            for (int col = 0; col < kSphereMapWidth; ++col) {
                const double u = (col + 0.5) / kSphereMapWidth, v = (row + 0.5) / kSphereMapHeight;
                const double phi = 2.0 * kPi * (u - 0.5), theta = kPi * v;
                const Vec3 n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
                requests.push_back({&material, facet_of(n), shadow_at(*scene.tracer, centre + radius * n, n)});
            }
        }
        const auto t = thermal::predict_surface_temperatures(*weather, requests, time_s, options);
        obj.temperature = TemperatureField::texture(std::vector<float>(t.begin(), t.end()), kSphereMapWidth, kSphereMapHeight);
    }
}

}  // namespace tirpol::simulation
