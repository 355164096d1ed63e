// `tirpol therm`: surface temperatures of a thermal model's objects at a time, a CSV of them, and a
// 24-hour plot of every object's surface temperature (drawn with OpenCV).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "cli.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/simulation/thermal/civil_time.h"
#include "tirpol/simulation/thermal/thermal_config.h"

namespace tirpol::cli {

namespace {

struct ThermArgs {
    std::string file;
    std::string at;
    std::string csv;
    std::string plot;
    bool json = false;
};

struct ObjectResult {
    const thermal::ThermalObject* object;
    std::vector<thermal::TemperatureSample> history;  // last 24 h when plotting, else only the final sample
};

// "Nice" tick step (1, 2 or 5 × 10^k) giving about `target` intervals over `span`.
double nice_step(double span, int target) {
    const double raw = span / target;
    const double mag = std::pow(10.0, std::floor(std::log10(raw)));
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (raw <= m * mag) return m * mag;
    return 10.0 * mag;
}

void draw_plot(const std::string& path, const std::vector<ObjectResult>& results, const thermal::ThermalScene& scene,
               double end_s) {
    const int width = 1200, height = 680, left = 90, right = 300, top = 60, bottom = 80;
    const int pw = width - left - right, ph = height - top - bottom;
    cv::Mat img(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
    const double t0 = end_s - 24 * 3600.0;
    double lo = 1e9, hi = -1e9;
    for (const auto& r : results)
        for (const auto& s : r.history) {
            lo = std::min({lo, s.surface_temperature_k - 273.15, s.air_temperature_k - 273.15});
            hi = std::max({hi, s.surface_temperature_k - 273.15, s.air_temperature_k - 273.15});
        }
    const double step = nice_step(std::max(hi - lo, 1.0), 6);
    lo = std::floor(lo / step) * step;
    hi = std::ceil(hi / step) * step;
    auto px = [&](double t) { return left + static_cast<int>(std::lround((t - t0) / (24 * 3600.0) * pw)); };
    auto py = [&](double c) { return top + ph - static_cast<int>(std::lround((c - lo) / (hi - lo) * ph)); };
    const auto font = cv::FONT_HERSHEY_SIMPLEX;
    const cv::Scalar black(0, 0, 0), grid(225, 225, 225);
    // y grid and ticks
    for (double c = lo; c <= hi + 1e-9; c += step) {
        cv::line(img, {left, py(c)}, {left + pw, py(c)}, grid, 1);
        cv::line(img, {left - 6, py(c)}, {left, py(c)}, black, 1);
        char label[32];
        std::snprintf(label, sizeof label, "%g", c);
        int base = 0;
        const cv::Size sz = cv::getTextSize(label, font, 0.5, 1, &base);
        cv::putText(img, label, {left - 10 - sz.width, py(c) + sz.height / 2}, font, 0.5, black, 1, cv::LINE_AA);
    }
    // x grid and ticks every 3 h, labelled with local clock time
    for (int h = 0; h <= 24; h += 3) {
        const double t = t0 + h * 3600.0;
        cv::line(img, {px(t), top}, {px(t), top + ph}, grid, 1);
        cv::line(img, {px(t), top + ph}, {px(t), top + ph + 6}, black, 1);
        const std::string label = thermal::format_time(t, scene.site.utc_offset_h).substr(11, 5);
        int base = 0;
        const cv::Size sz = cv::getTextSize(label, font, 0.5, 1, &base);
        cv::putText(img, label, {px(t) - sz.width / 2, top + ph + 24}, font, 0.5, black, 1, cv::LINE_AA);
    }
    cv::rectangle(img, {left, top}, {left + pw, top + ph}, black, 1);
    const std::string end_label = thermal::format_time(end_s, scene.site.utc_offset_h);
    cv::putText(img, "Surface temperature, 24 h to " + end_label, {left, 35}, font, 0.7, black, 1, cv::LINE_AA);
    char xlabel[96];
    std::snprintf(xlabel, sizeof xlabel, "local standard time (UTC%+g h)", scene.site.utc_offset_h);
    cv::putText(img, xlabel, {left + pw / 2 - 150, height - 25}, font, 0.6, black, 1, cv::LINE_AA);
    cv::putText(img, "deg C", {left - 70, top - 10}, font, 0.6, black, 1, cv::LINE_AA);

    static const cv::Scalar kPalette[] = {{180, 119, 31}, {14, 127, 255}, {44, 160, 44}, {40, 39, 214}, {189, 103, 148},
                                          {75, 86, 140},  {194, 119, 227}, {34, 189, 188}, {207, 190, 23}};
    int legend_y = top + 10;
    auto legend = [&](const std::string& text, const cv::Scalar& colour, bool dashed) {
        const int x = left + pw + 20;
        if (dashed) {
            for (int d = 0; d < 30; d += 10) cv::line(img, {x + d, legend_y}, {x + d + 5, legend_y}, colour, 2, cv::LINE_AA);
        } else {
            cv::line(img, {x, legend_y}, {x + 30, legend_y}, colour, 2, cv::LINE_AA);
        }
        cv::putText(img, text, {x + 38, legend_y + 5}, font, 0.45, black, 1, cv::LINE_AA);
        legend_y += 22;
    };
    // Air temperature (the same for all objects), dashed grey.
    if (!results.empty()) {
        const auto& h = results.front().history;
        for (std::size_t i = 1; i < h.size(); i += 2)
            cv::line(img, {px(h[i - 1].time_s), py(h[i - 1].air_temperature_k - 273.15)},
                     {px(h[i].time_s), py(h[i].air_temperature_k - 273.15)}, cv::Scalar(120, 120, 120), 2, cv::LINE_AA);
        legend("air", cv::Scalar(120, 120, 120), true);
    }
    for (std::size_t k = 0; k < results.size(); ++k) {
        const cv::Scalar colour = kPalette[k % std::size(kPalette)];
        std::vector<cv::Point> pts;
        for (const auto& s : results[k].history) pts.emplace_back(px(s.time_s), py(s.surface_temperature_k - 273.15));
        cv::polylines(img, pts, false, colour, 2, cv::LINE_AA);
        const auto& obj = *results[k].object;
        legend(obj.name + " (" + scene.materials[obj.material].name + ")", colour, false);
    }
    std::vector<unsigned char> png;
    if (!cv::imencode(".png", img, png)) fail("could not encode the plot {}", path);
    write_file_atomic(path, std::string(png.begin(), png.end()));
}

void run_therm(const ThermArgs& a) {
    const thermal::ThermalScene scene = thermal::load_thermal_scene(a.file);
    double at = 0.0;
    if (!a.at.empty()) {
        at = thermal::parse_time(a.at, scene.site.utc_offset_h, "--at");
    } else if (scene.time_s) {
        at = *scene.time_s;
    } else {
        fail("{}: no `time:` entry; give the time with --at", a.file);
    }
    const bool plot = !a.plot.empty();
    const double history_s = plot ? 24 * 3600.0 : 0.0;
    const double start = at - history_s - scene.options.spin_up_hours * 3600.0;
    std::vector<ObjectResult> results;
    for (const auto& obj : scene.objects) {
        const double shadow = obj.shadow_fraction;
        const thermal::ShadowFunction shadow_fn = [shadow](double, const Vec3&) { return shadow; };
        auto history = thermal::simulate_facet(*scene.weather, scene.materials[obj.material], obj.facet, start, at,
                                               at - history_s, plot ? 900.0 : scene.options.time_step_s, scene.options,
                                               shadow_fn);
        results.push_back({&obj, std::move(history)});
    }
    std::ostringstream csv;
    csv << "object,material,tilt_deg,azimuth_deg,shadow_fraction,temperature_k,temperature_c,air_temperature_c,"
           "absorbed_solar_w_m2,absorbed_longwave_w_m2,emitted_longwave_w_m2,convection_w_m2\n";
    nlohmann::json out;
    out["time"] = thermal::format_time(at, scene.site.utc_offset_h);
    out["site"] = {{"name", scene.site.name}, {"latitude_deg", scene.site.latitude_deg},
                   {"longitude_deg", scene.site.longitude_deg}, {"utc_offset_h", scene.site.utc_offset_h}};
    out["objects"] = nlohmann::json::array();
    if (!a.json)
        std::printf("%s at %s (%s)\n%-22s %-14s %8s %8s %9s %9s\n", a.file.c_str(), out["time"].get<std::string>().c_str(),
                    scene.site.name.c_str(), "object", "material", "T (K)", "T (°C)", "air (°C)", "solar W/m²");
    for (const auto& r : results) {
        const auto& s = r.history.back();
        const auto& obj = *r.object;
        const std::string& mat = scene.materials[obj.material].name;
        const double tc = s.surface_temperature_k - 273.15, air_c = s.air_temperature_k - 273.15;
        if (!a.json)
            std::printf("%-22s %-14s %8.2f %8.2f %9.2f %9.1f\n", obj.name.c_str(), mat.c_str(), s.surface_temperature_k, tc,
                        air_c, s.fluxes.absorbed_shortwave);
        csv << obj.name << ',' << mat << ',' << obj.facet.tilt_deg << ',' << obj.facet.azimuth_deg << ','
            << obj.shadow_fraction << ',' << s.surface_temperature_k << ',' << tc << ',' << air_c << ','
            << s.fluxes.absorbed_shortwave << ',' << s.fluxes.absorbed_longwave << ',' << s.fluxes.emitted_longwave << ','
            << s.fluxes.convection << '\n';
        out["objects"].push_back({{"name", obj.name}, {"material", mat}, {"temperature_k", s.surface_temperature_k},
                                  {"air_temperature_k", s.air_temperature_k}});
    }
    if (!a.csv.empty()) write_file_atomic(a.csv, csv.str());
    if (plot) draw_plot(a.plot, results, scene, at);
    if (a.json) std::printf("%s\n", out.dump(2).c_str());
}

void register_therm(CLI::App& app) {
    auto args = std::make_shared<ThermArgs>();
    auto* cmd = app.add_subcommand("therm", "Surface temperatures from weather (1D slab model) and a 24-hour plot");
    cmd->add_option("file", args->file, "Thermal YAML (docs/thermal.md)")->required()->check(CLI::ExistingFile);
    cmd->add_option("--at", args->at, "Time, ISO 8601 (no offset: the site's standard time); default: the file's `time`");
    cmd->add_option("--csv", args->csv, "Write each object's temperature and surface balance to this CSV");
    cmd->add_option("--plot", args->plot, "Write a 24-hour surface-temperature plot (PNG)");
    cmd->add_flag("--json", args->json, "Print JSON (keys in docs/thermal.md)");
    cmd->callback([args] { run_therm(*args); });
}

}  // namespace

TIRPOL_REGISTER_COMMAND(310, register_therm);

}  // namespace tirpol::cli
