#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

#include "tirpol/core/error.h"
#include "tirpol/sweep/sweep_run.h"
#include "tirpol/thermal/civil_time.h"

namespace tirpol::sweep {

namespace {

constexpr std::size_t kMaxPoints = 100000;

bool starts_with(const std::string& s, std::string_view prefix) { return s.rfind(prefix, 0) == 0; }

/// Compact YAML-like text of a value: scalars as written, lists "[a, b]", mappings "{k: v}".
std::string value_text(const ConfigNode& node) {
    if (node.is_scalar()) return node.as<std::string>();
    if (node.is_null()) return "null";
    std::string out;
    if (node.is_sequence()) {
        for (const auto& e : node.elements()) out += (out.empty() ? "" : ", ") + value_text(e);
        return "[" + out + "]";
    }
    for (const auto& key : node.keys())
        out += (out.empty() ? "" : ", ") + key + ": " + value_text(node.at(key));
    return "{" + out + "}";
}

std::optional<double> number_of(const ConfigNode& node) {
    if (!node.is_scalar()) return std::nullopt;
    try {
        return node.as<double>();
    } catch (const Error&) {
        return std::nullopt;
    }
}

/// Object names of a scene file, as the loader names them.
std::vector<std::string> object_names(const ConfigNode& scene) {
    std::vector<std::string> names;
    const auto objects = scene.at("objects").elements();
    for (std::size_t i = 0; i < objects.size(); ++i)
        names.push_back(objects[i].get_or<std::string>("name", fmt::format("object{}", i)));
    return names;
}

/// A library material file ready to be written inline in a scene: its one relative file reference
/// (the n, k table, docs/materials.md) made absolute, since inline it would resolve against the
/// scene's folder.
ConfigNode inlinable_material(const std::filesystem::path& file) {
    const ConfigNode material = ConfigNode::load_file(file);
    const auto index = material.find("refractive_index");
    if (!index || !index->is_map() || !index->has("file")) return material;
    std::string absolute = index->resolve_path(index->get<std::string>("file")).string(),
                quoted = "'";
    for (char c : absolute) quoted += c == '\'' ? std::string("''") : std::string(1, c);
    return material.with_value("refractive_index.file",
                               ConfigNode::parse(quoted + "'", file.string()));
}

/// `materials.<name>.<path>`: each object whose material is the library material <name> gets it
/// inline with the override; an inline material of that name is overridden in place.
ConfigNode with_material_value(const ConfigNode& scene, const std::string& name,
                               const std::string& path, const ConfigNode& value) {
    // The scene loader's rule for the library folder (docs/scene-format.md, materials_dir).
    const auto dir_node = scene.find("materials_dir");
    const std::filesystem::path dir = dir_node ? dir_node->resolve_path(dir_node->as<std::string>())
                                               : scene.resolve_path("../materials");
    ConfigNode out = scene;
    std::vector<std::string> used;
    bool found = false;
    const auto objects = scene.at("objects").elements();
    for (std::size_t i = 0; i < objects.size(); ++i) {
        const ConfigNode material = objects[i].at("material");
        const std::string object_path = fmt::format("objects[{}].material", i);
        if (material.is_scalar()) {
            used.push_back(material.as<std::string>());
            if (used.back() != name) continue;
            const auto file = dir / (name + ".yaml");
            if (!std::filesystem::is_regular_file(file))
                material.fail(
                    fmt::format("materials.{}: material file not found: {}", name, file.string()));
            out = out.with_value(object_path, inlinable_material(file).with_value(path, value));
            found = true;
        } else if (material.is_map() && material.has("name")) {
            used.push_back(material.get<std::string>("name"));
            if (used.back() != name) continue;
            out = out.with_value(object_path + "." + path, value);
            found = true;
        }
    }
    if (!found) {
        const std::string hint = closest_match(name, used);
        fail("no object uses the material '{}'{} (materials used: {})", name,
             hint.empty() ? "" : " — did you mean '" + hint + "'?", fmt::join(used, ", "));
    }
    return out;
}

void apply(PointConfig& config, const std::string& parameter, const ConfigNode& value) {
    if (starts_with(parameter, "sensor.")) {
        if (!config.sensor)
            fail("'{}' varies the sensor model, but the sweep names no `sensor:` file", parameter);
        config.sensor = config.sensor->with_value(parameter.substr(7), value);
    } else if (starts_with(parameter, "materials.")) {
        const std::size_t dot = parameter.find('.', 10);
        if (dot == std::string::npos)
            fail("'{}': expected materials.<name>.<field path>", parameter);
        config.scene = with_material_value(config.scene, parameter.substr(10, dot - 10),
                                           parameter.substr(dot + 1), value);
    } else {
        config.scene = config.scene.with_value(parameter, value);
    }
}

/// Applies `value` to the base files once, so that an unknown parameter is reported at load time,
/// at the sweep file's `where`.
void check_parameter(const SweepSpec& spec, const std::string& parameter, const ConfigNode& value,
                     const ConfigNode& where) {
    PointConfig config{spec.scene, spec.sensor};
    try {
        apply(config, parameter, value);
    } catch (const Error& e) {
        where.fail(fmt::format("unknown parameter '{}': {}", parameter, e.what()));
    }
}

/// Values of a range `{from, to, step}` (numbers) or `{from, to, step_h}` (times, for `time`).
std::vector<ConfigNode> range_values(const std::string& parameter, const ConfigNode& node) {
    const bool is_time = parameter == "time";
    node.check_keys({"from", "to", is_time ? "step_h" : "step"});
    const std::string step_key = is_time ? "step_h" : "step";
    const double step = node.get<double>(step_key);
    if (!(step > 0.0)) node.at(step_key).fail("expected a positive step");
    double from = 0.0, to = 0.0;
    if (is_time) {
        from = thermal::parse_time(node.get<std::string>("from"), 0.0, node.at("from").location()) /
               3600.0;
        to = thermal::parse_time(node.get<std::string>("to"), 0.0, node.at("to").location()) /
             3600.0;
    } else {
        from = node.get<double>("from");
        to = node.get<double>("to");
    }
    if (to < from) node.at("to").fail(fmt::format("expected `to` ≥ `from`"));
    const double count = std::floor((to - from) / step + 1e-9) + 1.0;
    if (count > static_cast<double>(kMaxPoints))
        node.fail(fmt::format("{} values: more than {}", count, kMaxPoints));
    std::vector<ConfigNode> values;
    for (int i = 0; i < static_cast<int>(count); ++i) {
        const double v = from + i * step;
        std::string text = fmt::format("{}", v);
        if (is_time) {
            // Written without an offset, so the scene reads it in the site's standard time like its
            // own `time`.
            const thermal::CivilTime c = thermal::to_civil(std::round(v * 3600.0), 0.0);
            text = fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}", c.year, c.month, c.day, c.hour,
                               c.minute);
        }
        values.push_back(ConfigNode::parse(
            text, fmt::format("{} (value {} of the range)", node.location(), i + 1)));
    }
    return values;
}

Axis axis_of(const std::string& parameter, const ConfigNode& node) {
    Axis axis{parameter, {}, {}, {}, parameter};
    if (node.is_map()) {
        axis.values = range_values(parameter, node);
    } else if (node.is_sequence()) {
        axis.values = node.elements();
    } else {
        node.fail("expected a list of values or a range {from, to, step}");
    }
    if (axis.values.empty()) node.fail(fmt::format("the axis '{}' has no values", parameter));
    bool numeric = true;
    for (const auto& v : axis.values) {
        axis.labels.push_back(value_text(v));
        numeric = numeric && number_of(v).has_value();
    }
    for (std::size_t i = 0; i < axis.values.size(); ++i) {
        if (parameter == "time") {
            const double t0 = thermal::parse_time(axis.labels[0], 0.0, axis.values[0].location());
            axis.coordinates.push_back(
                (thermal::parse_time(axis.labels[i], 0.0, axis.values[i].location()) - t0) /
                3600.0);
            axis.coordinate_label = "time [h after " + axis.labels[0] + "]";
        } else if (numeric) {
            axis.coordinates.push_back(*number_of(axis.values[i]));
        } else {
            axis.coordinates.push_back(static_cast<double>(i));
            axis.coordinate_label = parameter + " [value number]";
        }
    }
    return axis;
}

std::pair<double, double> sector_of(const ConfigNode& node) {
    const auto v = node.as<std::vector<double>>();
    if (v.size() != 2 || !(v[1] > v[0]) || v[1] - v[0] > 360.0)
        node.fail("expected [from_deg, to_deg] with from < to ≤ from + 360");
    return {v[0], v[1]};
}

RegionSpec region_of(const std::string& name, const ConfigNode& node,
                     const std::vector<std::string>& objects) {
    node.check_keys({"object", "sectors_deg", "polygon"});
    RegionSpec r{name, node.get_or<std::string>("object", ""), {}, std::nullopt, node.location()};
    if (!r.object.empty() && std::find(objects.begin(), objects.end(), r.object) == objects.end()) {
        const std::string hint = closest_match(r.object, objects);
        node.at("object").fail(fmt::format(
            "the base scene has no object '{}'{} (objects: {})", r.object,
            hint.empty() ? "" : " — did you mean '" + hint + "'?", fmt::join(objects, ", ")));
    }
    if (auto s = node.find("sectors_deg")) {
        if (r.object.empty())
            s->fail("sectors are taken around an object's centre: give `object` too");
        for (const auto& e : s->elements()) r.sectors_deg.push_back(sector_of(e));
        if (r.sectors_deg.empty()) s->fail("expected at least one [from_deg, to_deg]");
    }
    if (auto p = node.find("polygon")) {
        report::Region region{name, {}, p->location()};
        for (const auto& v : p->elements()) {
            const auto xy = v.as<std::vector<double>>();
            if (xy.size() != 2) v.fail("expected a vertex [x, y] in pixels");
            region.polygon.push_back({xy[0], xy[1]});
        }
        if (region.polygon.size() < 3) p->fail("a polygon needs at least 3 vertices");
        r.polygon = region;
    }
    if (r.object.empty() && !r.polygon) node.fail("a region needs an `object` and/or a `polygon`");
    return r;
}

}  // namespace

std::uint64_t point_seed(std::uint64_t sweep_seed, std::size_t index) {
    std::uint64_t z = sweep_seed + 0x9E3779B97F4A7C15ULL * (static_cast<std::uint64_t>(index) + 1);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return (z ^ (z >> 31)) >> 1;
}

SweepSpec load_sweep(const std::filesystem::path& path) {
    const ConfigNode root = ConfigNode::load_file(path);
    root.check_keys({"scene", "sensor", "combine", "seed", "set", "axes", "regions", "contrasts"});
    const ConfigNode scene_node = root.at("scene");
    const auto scene_path = scene_node.resolve_path(scene_node.as<std::string>());
    if (!std::filesystem::is_regular_file(scene_path))
        scene_node.fail("scene file not found: " + scene_path.string());
    SweepSpec spec{std::filesystem::absolute(path),
                   ConfigNode::load_file(scene_path),
                   std::nullopt,
                   {},
                   {},
                   Combine::Grid,
                   1,
                   {},
                   {}};
    if (auto s = root.find("sensor")) {
        const auto sensor_path = s->resolve_path(s->as<std::string>());
        if (!std::filesystem::is_regular_file(sensor_path))
            s->fail("sensor file not found: " + sensor_path.string());
        spec.sensor = ConfigNode::load_file(sensor_path);
    }
    if (auto c = root.find("combine")) {
        const std::string combine = c->as<std::string>();
        if (combine != "grid" && combine != "list")
            c->fail("expected grid or list, got '" + combine + "'");
        spec.combine = combine == "grid" ? Combine::Grid : Combine::List;
    }
    if (auto s = root.find("seed")) {
        const double seed = s->as<double>();
        if (seed < 0 || seed != std::floor(seed) || seed > 9.0e15)
            s->fail("expected a non-negative whole number");
        spec.seed = static_cast<std::uint64_t>(seed);
    }
    if (auto set = root.find("set")) {
        for (const auto& key : set->keys()) {
            check_parameter(spec, key, set->at(key), set->at(key));
            spec.fixed.emplace_back(key, set->at(key));
        }
    }
    const ConfigNode axes = root.at("axes");
    const auto axis_names = axes.keys();
    if (axis_names.empty()) axes.fail("expected at least one axis (parameter: [values])");
    std::size_t points = 1;
    for (const auto& name : axis_names) {
        Axis axis = axis_of(name, axes.at(name));
        check_parameter(spec, name, axis.values.front(), axes.at(name));
        if (spec.combine == Combine::List && !spec.axes.empty() &&
            axis.values.size() != spec.axes[0].values.size())
            axes.at(name).fail(fmt::format(
                "combine: list needs axes of equal length: {} values here, {} in '{}'",
                axis.values.size(), spec.axes[0].values.size(), spec.axes[0].parameter));
        points = spec.combine == Combine::List ? axis.values.size() : points * axis.values.size();
        if (points > kMaxPoints) axes.at(name).fail(fmt::format("more than {} points", kMaxPoints));
        spec.axes.push_back(std::move(axis));
    }

    const auto objects = object_names(spec.scene);
    if (auto regions = root.find("regions")) {
        for (const auto& name : regions->keys())
            spec.regions.push_back(region_of(name, regions->at(name), objects));
    } else {
        for (const auto& object : objects)
            spec.regions.push_back({object, object, {}, std::nullopt, root.location()});
    }
    if (auto contrasts = root.find("contrasts")) {
        std::vector<std::string> names;
        for (const auto& r : spec.regions) names.push_back(r.name);
        for (const auto& name : contrasts->keys()) {
            const ConfigNode c = contrasts->at(name);
            c.check_keys({"a", "b"});
            ContrastSpec contrast{name, c.get<std::string>("a"), c.get<std::string>("b")};
            for (const auto* key : {"a", "b"}) {
                const std::string region = c.get<std::string>(key);
                if (std::find(names.begin(), names.end(), region) == names.end()) {
                    const std::string hint = closest_match(region, names);
                    c.at(key).fail(
                        fmt::format("no region '{}'{} (regions: {})", region,
                                    hint.empty() ? "" : " — did you mean '" + hint + "'?",
                                    fmt::join(names, ", ")));
                }
            }
            spec.contrasts.push_back(contrast);
        }
    }
    return spec;
}

std::vector<SweepPoint> sweep_points(const SweepSpec& spec) {
    std::size_t count = spec.combine == Combine::List ? spec.axes[0].values.size() : 1;
    if (spec.combine == Combine::Grid)
        for (const auto& axis : spec.axes) count *= axis.values.size();
    const int digits = std::max(4, static_cast<int>(std::to_string(count - 1).size()));
    std::vector<SweepPoint> points;
    for (std::size_t i = 0; i < count; ++i) {
        SweepPoint p{i, std::vector<std::size_t>(spec.axes.size()), point_seed(spec.seed, i), ""};
        std::size_t rest = i;
        for (std::size_t a = spec.axes.size(); a-- > 0;) {
            const std::size_t n = spec.axes[a].values.size();
            p.value_index[a] = spec.combine == Combine::List ? i : rest % n;
            rest /= n;
        }
        p.id = fmt::format("p{:0{}}", i, digits);
        points.push_back(std::move(p));
    }
    return points;
}

PointConfig point_config(const SweepSpec& spec, const SweepPoint& point) {
    PointConfig config{spec.scene, spec.sensor};
    for (const auto& [parameter, value] : spec.fixed) apply(config, parameter, value);
    for (std::size_t a = 0; a < spec.axes.size(); ++a)
        apply(config, spec.axes[a].parameter, spec.axes[a].values[point.value_index[a]]);
    return config;
}

}  // namespace tirpol::sweep
