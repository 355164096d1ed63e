#include <algorithm>
#include <array>
#include <sstream>

#include "tirpol/core/quicklook.h"
#include "tirpol/core/radiometry.h"
#include "tirpol/thermal/civil_time.h"
#include "tirpol/thermal/thermal_config.h"

namespace tirpol::thermal {

namespace {
constexpr double kHistoryS = 24 * 3600.0;
constexpr double kHistoryStepS = 900.0;
}  // namespace

ThermalRun simulate_thermal_scene(const ThermalScene& scene, double end_s, bool with_24h_history) {
    const double history_s = with_24h_history ? kHistoryS : 0.0;
    const double start = end_s - history_s - scene.options.spin_up_hours * 3600.0;
    ThermalRun run;
    run.end_s = end_s;
    for (const auto& obj : scene.objects) {
        const double shadow = obj.shadow_fraction;
        const ShadowFunction shadow_fn = [shadow](double, const Vec3&) { return shadow; };
        auto samples = simulate_facet(*scene.weather, scene.materials[obj.material], obj.facet,
                                      start, end_s, end_s - history_s,
                                      with_24h_history ? kHistoryStepS : scene.options.time_step_s,
                                      scene.options, shadow_fn);
        run.objects.push_back({&obj, std::move(samples)});
    }
    return run;
}

std::string thermal_run_csv(const ThermalScene& scene, const ThermalRun& run) {
    std::ostringstream csv;
    csv << "object,material,tilt_deg,azimuth_deg,shadow_fraction,temperature_k,temperature_c,"
           "air_temperature_c,absorbed_solar_w_m2,absorbed_longwave_w_m2,emitted_longwave_w_m2,"
           "convection_w_m2\n";
    for (const auto& r : run.objects) {
        const auto& s = r.samples.back();
        const auto& obj = *r.object;
        csv << obj.name << ',' << scene.materials[obj.material].name << ',' << obj.facet.tilt_deg
            << ',' << obj.facet.azimuth_deg << ',' << obj.shadow_fraction << ','
            << s.surface_temperature_k << ',' << s.surface_temperature_k - kZeroCelsiusK << ','
            << s.air_temperature_k - kZeroCelsiusK << ',' << s.fluxes.absorbed_shortwave << ','
            << s.fluxes.absorbed_longwave << ',' << s.fluxes.emitted_longwave << ','
            << s.fluxes.convection << '\n';
    }
    return csv.str();
}

nlohmann::json thermal_run_json(const ThermalScene& scene, const ThermalRun& run) {
    nlohmann::json out;
    out["time"] = format_time(run.end_s, scene.site.utc_offset_h);
    out["site"] = {{"name", scene.site.name},
                   {"latitude_deg", scene.site.latitude_deg},
                   {"longitude_deg", scene.site.longitude_deg},
                   {"utc_offset_h", scene.site.utc_offset_h}};
    out["objects"] = nlohmann::json::array();
    for (const auto& r : run.objects) {
        const auto& s = r.samples.back();
        out["objects"].push_back({{"name", r.object->name},
                                  {"material", scene.materials[r.object->material].name},
                                  {"temperature_k", s.surface_temperature_k},
                                  {"air_temperature_k", s.air_temperature_k}});
    }
    return out;
}

void write_thermal_history_plot(const std::filesystem::path& path, const ThermalScene& scene,
                                const ThermalRun& run) {
    static const std::array<std::uint8_t, 3> kPalette[] = {
        {31, 119, 180}, {255, 127, 14},  {44, 160, 44},  {214, 39, 40}, {148, 103, 189},
        {140, 86, 75},  {227, 119, 194}, {188, 189, 34}, {23, 190, 207}};
    const double end_s = run.end_s;
    std::vector<PlotSeries> series;
    if (!run.objects.empty()) {
        PlotSeries air{"air", {}, {}, {120, 120, 120}, false, true};
        for (const auto& s : run.objects.front().samples) {
            air.x.push_back((s.time_s - end_s) / 3600.0);
            air.y.push_back(s.air_temperature_k - kZeroCelsiusK);
        }
        series.push_back(std::move(air));
    }
    for (std::size_t k = 0; k < run.objects.size(); ++k) {
        const auto& obj = *run.objects[k].object;
        PlotSeries line{obj.name + " (" + scene.materials[obj.material].name + ")",
                        {},
                        {},
                        kPalette[k % std::size(kPalette)]};
        for (const auto& s : run.objects[k].samples) {
            line.x.push_back((s.time_s - end_s) / 3600.0);
            line.y.push_back(s.surface_temperature_k - kZeroCelsiusK);
        }
        series.push_back(std::move(line));
    }
    LinePlotOptions options;
    options.title = "Surface temperature, 24 h to " + format_time(end_s, scene.site.utc_offset_h);
    options.x_label = "hours before that time";
    options.y_label = "temperature (deg C)";
    options.x_min = -24.0;
    options.x_max = 0.0;
    // Head-room above the data for the legend.
    double lo = 1e300, hi = -1e300;
    for (const auto& line : series)
        for (double y : line.y) lo = std::min(lo, y), hi = std::max(hi, y);
    options.y_min = lo - 0.05 * (hi - lo + 1.0);
    options.y_max = hi + (0.12 + 0.05 * static_cast<double>(series.size())) * (hi - lo + 1.0);
    options.width = 1100;
    options.height = 650;
    write_line_plot(path, series, options);
}

}  // namespace tirpol::thermal
