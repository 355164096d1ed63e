// Field-log weather CSV (format in docs/thermal.md).

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>

#include "csv_fields.h"
#include "tirpol/core/config.h"
#include "tirpol/core/error.h"
#include "tirpol/core/output_guard.h"
#include "tirpol/thermal/civil_time.h"
#include "tirpol/thermal/sky_longwave.h"
#include "tirpol/thermal/solar_position.h"
#include "tirpol/thermal/surface_temperature.h"

namespace tirpol::thermal {

namespace {

/// Solar constant, W/m² (Kopp & Lean, Geophys. Res. Lett. 38 (2011) L01706: 1360.8 ± 0.5).
constexpr double kSolarConstant = 1360.8;

const std::vector<std::string> kKnownColumns = {"time",
                                                "air_temperature_c",
                                                "relative_humidity_pct",
                                                "dew_point_c",
                                                "wind_speed_m_s",
                                                "global_horizontal_w_m2",
                                                "direct_normal_w_m2",
                                                "diffuse_horizontal_w_m2",
                                                "sky_ir_w_m2",
                                                "pressure_pa",
                                                "opaque_sky_cover_tenths"};

struct Range {
    double lo, hi;
};
const std::map<std::string, Range> kRanges = {{"air_temperature_c", {-90, 70}},
                                              {"relative_humidity_pct", {0.1, 110}},
                                              {"dew_point_c", {-90, 70}},
                                              {"wind_speed_m_s", {0, 40}},
                                              {"global_horizontal_w_m2", {0, 1500}},
                                              {"direct_normal_w_m2", {0, 1400}},
                                              {"diffuse_horizontal_w_m2", {0, 1000}},
                                              {"sky_ir_w_m2", {0, 1000}},
                                              {"pressure_pa", {31000, 120000}},
                                              {"opaque_sky_cover_tenths", {0, 10}}};

}  // namespace

WeatherSeries load_weather_csv(const std::filesystem::path& path, const Site& site,
                               double max_gap_h) {
    check_input_file(path);
    std::ifstream in(path);
    if (!in) fail("cannot open weather file {}", path.string());
    const std::string file = path.string();
    std::string line;
    int line_number = 0;
    std::vector<std::string> header;
    while (std::getline(in, line)) {
        ++line_number;
        if (line.empty() || line[0] == '#' || line == "\r") continue;
        header = detail::split_csv_line(line);
        break;
    }
    if (header.empty()) fail("{}: no header line", file);
    std::map<std::string, std::size_t> col;
    for (std::size_t i = 0; i < header.size(); ++i) {
        if (std::find(kKnownColumns.begin(), kKnownColumns.end(), header[i]) ==
            kKnownColumns.end()) {
            const std::string hint = closest_match(header[i], kKnownColumns);
            fail("{}:{}: unknown column '{}'{}", file, line_number, header[i],
                 hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint));
        }
        col[header[i]] = i;
    }
    for (const char* required :
         {"time", "air_temperature_c", "wind_speed_m_s", "global_horizontal_w_m2"})
        if (!col.count(required)) fail("{}: missing required column '{}'", file, required);
    if (!col.count("relative_humidity_pct") && !col.count("dew_point_c"))
        fail("{}: needs a 'relative_humidity_pct' or a 'dew_point_c' column", file);
    const bool has_split = col.count("direct_normal_w_m2") && col.count("diffuse_horizontal_w_m2");
    if (!has_split && (col.count("direct_normal_w_m2") || col.count("diffuse_horizontal_w_m2")))
        fail("{}: give both 'direct_normal_w_m2' and 'diffuse_horizontal_w_m2' or neither", file);
    if (!col.count("sky_ir_w_m2") && !col.count("opaque_sky_cover_tenths"))
        fail("{}: needs 'sky_ir_w_m2' (measured) or 'opaque_sky_cover_tenths' for the sky longwave",
             file);

    std::vector<WeatherRecord> records;
    while (std::getline(in, line)) {
        ++line_number;
        if (line.empty() || line[0] == '#' || line == "\r") continue;
        const auto f = detail::split_csv_line(line);
        const std::string where = fmt::format("{}:{}", file, line_number);
        if (f.size() != header.size())
            fail("{}: {} fields, the header has {}", where, f.size(), header.size());
        auto value = [&](const std::string& name, bool required) -> double {
            const auto it = col.find(name);
            if (it == col.end()) return kMissing;
            const std::string& text = f[it->second];
            if (text.empty()) {
                if (required) fail("{}: column '{}' is empty", where, name);
                return kMissing;
            }
            const double v = detail::parse_number(text, where, name);
            const Range r = kRanges.at(name);
            if (!(v >= r.lo && v <= r.hi))
                fail("{}: {} = {} outside the plausible range [{}, {}]", where, name, v, r.lo,
                     r.hi);
            return v;
        };
        WeatherRecord w;
        w.time_s = parse_time(f[col["time"]], site.utc_offset_h, where + ": time");
        w.air_temperature_c = value("air_temperature_c", true);
        const bool has_dew = col.count("dew_point_c") > 0;
        if (has_dew) {
            w.dew_point_c = value("dew_point_c", true);
            w.relative_humidity_pct = relative_humidity_pct(w.air_temperature_c, w.dew_point_c);
        } else {
            w.relative_humidity_pct = value("relative_humidity_pct", true);
            w.dew_point_c =
                dew_point_c(w.air_temperature_c, std::min(100.0, w.relative_humidity_pct));
        }
        w.wind_speed_m_s = value("wind_speed_m_s", true);
        w.global_horizontal_w_m2 = value("global_horizontal_w_m2", true);
        w.pressure_pa = value("pressure_pa", false);
        if (std::isnan(w.pressure_pa)) w.pressure_pa = standard_pressure_pa(site.elevation_m);
        w.horizontal_ir_w_m2 = value("sky_ir_w_m2", false);
        w.opaque_sky_cover_tenths = value("opaque_sky_cover_tenths", false);
        if (std::isnan(w.horizontal_ir_w_m2) && std::isnan(w.opaque_sky_cover_tenths))
            fail("{}: both sky_ir_w_m2 and opaque_sky_cover_tenths are empty; one is needed",
                 where);
        if (has_split) {
            w.direct_normal_w_m2 = value("direct_normal_w_m2", true);
            w.diffuse_horizontal_w_m2 = value("diffuse_horizontal_w_m2", true);
        } else {
            // Erbs et al. (1982): diffuse fraction from the clearness index k_t = GHI / (E0 cos z).
            SpaInput spa;
            spa.unix_seconds = w.time_s;
            spa.latitude_deg = site.latitude_deg;
            spa.longitude_deg = site.longitude_deg;
            spa.elevation_m = site.elevation_m;
            const SolarPosition sun = solar_position(spa);
            const double cos_z = std::cos(deg_to_rad(sun.zenith_deg));
            // Below ~3.7° elevation the split is meaningless: all diffuse.
            if (cos_z < 0.065) {
                w.diffuse_horizontal_w_m2 = w.global_horizontal_w_m2;
                w.direct_normal_w_m2 = 0.0;
            } else {
                const double e0 = kSolarConstant / (sun.earth_radius_au * sun.earth_radius_au);
                const double kt = std::min(1.0, w.global_horizontal_w_m2 / (e0 * cos_z));
                w.diffuse_horizontal_w_m2 = erbs_diffuse_fraction(kt) * w.global_horizontal_w_m2;
                w.direct_normal_w_m2 =
                    (w.global_horizontal_w_m2 - w.diffuse_horizontal_w_m2) / cos_z;
            }
        }
        if (!records.empty()) {
            const double gap_h = (w.time_s - records.back().time_s) / 3600.0;
            if (gap_h <= 0.0)
                fail("{}: time {} is not after the previous record", where, f[col["time"]]);
            if (gap_h > max_gap_h)
                fail("{}: gap of {:.2f} h before {} (longest allowed {} h)", where, gap_h,
                     f[col["time"]], max_gap_h);
        }
        records.push_back(w);
    }
    return WeatherSeries(site, std::move(records), file, 0.0);
}

}  // namespace tirpol::thermal
