#include "tirpol/thermal/thermal_config.h"

#include <algorithm>

#include "tirpol/core/error.h"
#include "tirpol/thermal/civil_time.h"

namespace tirpol::thermal {

Site parse_site(const ConfigNode& node) {
    node.check_keys({"name", "latitude_deg", "longitude_deg", "utc_offset_h", "elevation_m"});
    Site s;
    s.name = node.get_or<std::string>("name", "");
    s.latitude_deg = node.get_in_range("latitude_deg", -90.0, 90.0);
    s.longitude_deg = node.get_in_range("longitude_deg", -180.0, 180.0);
    s.utc_offset_h = node.get_in_range("utc_offset_h", -14.0, 14.0);
    s.elevation_m =
        node.has("elevation_m") ? node.get_in_range("elevation_m", -500.0, 9000.0) : 0.0;
    return s;
}

std::shared_ptr<const WeatherSeries> load_weather(const ConfigNode& node,
                                                  const std::optional<Site>& site) {
    std::string file;
    std::optional<int> year;
    if (node.is_scalar()) {
        file = node.as<std::string>();
    } else {
        node.check_keys({"file", "year"});
        file = node.get<std::string>("file");
        if (node.has("year")) year = node.get<int>("year");
    }
    const auto path = node.resolve_path(file);
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".epw") {
        WeatherSeries w = load_epw(path, year);
        if (site)
            return std::make_shared<const WeatherSeries>(
                *site, w.records(), w.source(),
                0.5 * (w.records()[1].time_s - w.records()[0].time_s));
        return std::make_shared<const WeatherSeries>(std::move(w));
    }
    if (ext == ".csv") {
        if (!site)
            node.fail("a field-log CSV needs a `site` entry (latitude, longitude, UTC offset)");
        if (year) node.fail("`year` applies to EPW files only");
        return std::make_shared<const WeatherSeries>(load_weather_csv(path, *site));
    }
    node.fail(fmt::format("weather file '{}' should end in .epw or .csv", file));
}

ThermalOptions parse_thermal_options(const ConfigNode& node) {
    node.check_keys({"spin_up_hours", "time_step_s", "crank_nicolson", "sky_model",
                     "use_measured_sky_ir", "convection", "convection_w_m2_k", "ground_albedo",
                     "max_cell_thickness_m", "delta_t_s"});
    ThermalOptions o;
    if (node.has("spin_up_hours"))
        o.spin_up_hours = node.get_in_range("spin_up_hours", 0.0, 24.0 * 60);
    if (node.has("time_step_s")) o.time_step_s = node.get_in_range("time_step_s", 1.0, 3600.0);
    if (node.get_or<bool>("crank_nicolson", false)) o.implicit_weight = 0.5;
    if (node.has("sky_model")) {
        try {
            o.sky_model = parse_clear_sky_model(node.get<std::string>("sky_model"));
        } catch (const Error& e) {
            node.at("sky_model").fail(e.what());
        }
    }
    o.use_measured_sky_ir = node.get_or<bool>("use_measured_sky_ir", true);
    const std::string conv = node.get_or<std::string>("convection", "mcadams");
    if (conv == "mcadams") {
        o.convection = ConvectionModel::McAdams;
    } else if (conv == "fixed") {
        o.convection = ConvectionModel::Fixed;
        o.fixed_convection_w_m2_k = node.get_in_range("convection_w_m2_k", 0.0, 500.0);
    } else {
        node.at("convection").fail("expected 'mcadams' or 'fixed', got '" + conv + "'");
    }
    if (node.has("ground_albedo")) o.ground_albedo = node.get_in_range("ground_albedo", 0.0, 1.0);
    if (node.has("max_cell_thickness_m"))
        o.grid.max_cell_thickness_m = node.get_in_range("max_cell_thickness_m", 1e-5, 1.0);
    if (node.has("delta_t_s")) o.delta_t_s = node.get_in_range("delta_t_s", -1e5, 1e5);
    return o;
}

ThermalMaterial parse_thermal_material(const ConfigNode& node) {
    node.check_keys({"name", "solar_absorptivity", "thermal_emissivity", "layers", "back"});
    ThermalMaterial m;
    m.name = node.get<std::string>("name");
    m.solar_absorptivity = node.get_in_range("solar_absorptivity", 0.0, 1.0);
    m.thermal_emissivity = node.get_in_range("thermal_emissivity", 0.0, 1.0);
    const auto layers = node.at("layers").elements();
    if (layers.empty()) node.at("layers").fail("needs at least one layer");
    for (const auto& l : layers) {
        l.check_keys({"thickness_m", "conductivity_w_m_k", "density_kg_m3", "specific_heat_j_kg_k",
                      "cells"});
        Layer layer;
        layer.thickness_m = l.get_in_range("thickness_m", 1e-6, 100.0);
        layer.conductivity_w_m_k = l.get_in_range("conductivity_w_m_k", 1e-4, 1000.0);
        layer.density_kg_m3 = l.get_in_range("density_kg_m3", 0.1, 30000.0);
        layer.specific_heat_j_kg_k = l.get_in_range("specific_heat_j_kg_k", 1.0, 20000.0);
        layer.cells = l.get_or<int>("cells", 0);
        if (layer.cells < 0) l.at("cells").fail("expected a non-negative number of cells");
        m.slab.layers.push_back(layer);
    }
    if (auto back = node.find("back")) {
        back->check_keys({"kind", "temperature_c", "depth_m"});
        const std::string kind = back->get<std::string>("kind");
        if (kind == "adiabatic") {
            m.slab.back.kind = BackBoundary::Kind::Adiabatic;
        } else if (kind == "fixed" || kind == "ground") {
            m.slab.back.kind =
                kind == "fixed" ? BackBoundary::Kind::FixedTemperature : BackBoundary::Kind::Ground;
            m.slab.back.temperature_k =
                back->get_in_range("temperature_c", -100.0, 200.0) + kZeroCelsiusK;
            if (kind == "ground")
                m.slab.back.ground_depth_m =
                    back->has("depth_m") ? back->get_in_range("depth_m", 0.01, 20.0) : 1.0;
        } else {
            back->at("kind").fail("expected adiabatic, fixed or ground, got '" + kind + "'");
        }
    }
    return m;
}

ThermalScene load_thermal_scene(const std::filesystem::path& path) {
    const ConfigNode root = ConfigNode::load_file(path);
    root.check_keys({"site", "weather", "time", "thermal", "materials", "objects"});
    ThermalScene s;
    std::optional<Site> site;
    if (auto n = root.find("site")) site = parse_site(*n);
    s.weather = load_weather(root.at("weather"), site);
    s.site = s.weather->site();
    if (auto n = root.find("thermal")) s.options = parse_thermal_options(*n);
    if (auto n = root.find("time")) {
        try {
            s.time_s = parse_time(n->as<std::string>(), s.site.utc_offset_h, "time");
        } catch (const Error& e) {
            n->fail(e.what());
        }
    }
    for (const auto& m : root.at("materials").elements()) {
        s.materials.push_back(parse_thermal_material(m));
        for (std::size_t i = 0; i + 1 < s.materials.size(); ++i)
            if (s.materials[i].name == s.materials.back().name)
                m.at("name").fail("duplicate material name");
    }
    std::vector<std::string> names;
    for (const auto& m : s.materials) names.push_back(m.name);
    for (const auto& o : root.at("objects").elements()) {
        o.check_keys(
            {"name", "material", "tilt_deg", "azimuth_deg", "sky_view_factor", "shadow_fraction"});
        ThermalObject obj;
        obj.name = o.get<std::string>("name");
        const std::string mat = o.get<std::string>("material");
        const auto it = std::find(names.begin(), names.end(), mat);
        if (it == names.end()) {
            const std::string hint = closest_match(mat, names);
            o.at("material")
                .fail("no thermal material '" + mat + "'" +
                      (hint.empty() ? "" : "; did you mean '" + hint + "'?"));
        }
        obj.material = static_cast<std::size_t>(it - names.begin());
        obj.facet.tilt_deg = o.has("tilt_deg") ? o.get_in_range("tilt_deg", 0.0, 180.0) : 0.0;
        obj.facet.azimuth_deg =
            o.has("azimuth_deg") ? o.get_in_range("azimuth_deg", 0.0, 360.0) : 180.0;
        if (o.has("sky_view_factor"))
            obj.facet.sky_view_factor = o.get_in_range("sky_view_factor", 0.0, 1.0);
        if (o.has("shadow_fraction"))
            obj.shadow_fraction = o.get_in_range("shadow_fraction", 0.0, 1.0);
        s.objects.push_back(obj);
    }
    if (s.objects.empty()) root.at("objects").fail("needs at least one object");
    return s;
}

}  // namespace tirpol::thermal
