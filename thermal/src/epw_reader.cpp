// EnergyPlus weather (EPW) reader: field layout from the EnergyPlus "Auxiliary Programs" manual,
// section "Weather Converter Program / EnergyPlus Weather File (EPW) Data Dictionary".

#include <cmath>
#include <fstream>

#include "csv_fields.h"
#include "tirpol/core/error.h"
#include "tirpol/core/output_guard.h"
#include "tirpol/thermal/civil_time.h"
#include "tirpol/thermal/sky_longwave.h"
#include "tirpol/thermal/surface_temperature.h"

namespace tirpol::thermal {

namespace {

constexpr std::size_t kEpwFields = 35;
constexpr int kHeaderLines = 8;

// 0-based positions in a data line.
enum EpwField : std::size_t {
    kYear = 0,
    kMonth = 1,
    kDay = 2,
    kHour = 3,
    kMinute = 4,
    kDryBulb = 6,
    kDewPoint = 7,
    kRelHum = 8,
    kPressure = 9,
    kHorizontalIr = 12,
    kGlobal = 13,
    kDirect = 14,
    kDiffuse = 15,
    kWindSpeed = 21,
    kOpaqueSkyCover = 23,
    kAlbedo = 32,
};

struct FieldReader {
    const std::vector<std::string>& fields;
    std::string where;
    double number(std::size_t i, std::string_view name) const {
        return detail::parse_number(fields[i], where, name);
    }
    // A value that must be present: the missing code or a value outside [lo, hi] is an error.
    double required(std::size_t i, std::string_view name, double missing_code, double lo,
                    double hi) const {
        const double v = number(i, name);
        if (v == missing_code)
            fail("{}: {} is missing (code {}), and tirpol needs it", where, name, missing_code);
        if (!(v >= lo && v <= hi))
            fail("{}: {} = {} outside the plausible range [{}, {}]", where, name, v, lo, hi);
        return v;
    }
    // A whole number in [lo, hi] (date and time fields): checked before the cast, so a huge or
    // non-finite value is an error, never undefined behaviour.
    int integer(std::size_t i, std::string_view name, int lo, int hi) const {
        const double v = number(i, name);
        if (!(v >= lo && v <= hi) || v != std::floor(v))
            fail("{}: {} = {} is not a whole number in [{}, {}]", where, name, v, lo, hi);
        return static_cast<int>(v);
    }
    // A value that may be missing (→ NaN); present values must be in range.
    double optional(std::size_t i, std::string_view name, double missing_code, double lo,
                    double hi) const {
        const double v = number(i, name);
        if (v >= missing_code) return kMissing;
        if (!(v >= lo && v <= hi))
            fail("{}: {} = {} outside the plausible range [{}, {}]", where, name, v, lo, hi);
        return v;
    }
};

}  // namespace

WeatherSeries load_epw(const std::filesystem::path& path, std::optional<int> year) {
    check_input_file(path);
    std::ifstream in(path);
    if (!in) fail("cannot open weather file {}", path.string());
    const std::string file = path.string();
    std::string line;
    Site site;
    for (int n = 1; n <= kHeaderLines; ++n) {
        if (!std::getline(in, line))
            fail("{}: ends in the header (line {}); an EPW file has {} header lines", file, n,
                 kHeaderLines);
        const auto f = detail::split_csv_line(line);
        if (n == 1) {
            if (f.empty() || f[0] != "LOCATION" || f.size() < 10)
                fail(
                    "{}:1: expected "
                    "'LOCATION,city,state,country,source,WMO,latitude,longitude,time "
                    "zone,elevation'",
                    file);
            const std::string where = file + ":1";
            site.name = f[1];
            site.latitude_deg = detail::parse_number(f[6], where, "latitude");
            site.longitude_deg = detail::parse_number(f[7], where, "longitude");
            site.utc_offset_h = detail::parse_number(f[8], where, "time zone");
            site.elevation_m = detail::parse_number(f[9], where, "elevation");
            if (std::abs(site.latitude_deg) > 90.0 || std::abs(site.longitude_deg) > 180.0 ||
                std::abs(site.utc_offset_h) > 14.0)
                fail("{}: latitude {}, longitude {} or time zone {} out of range", where,
                     site.latitude_deg, site.longitude_deg, site.utc_offset_h);
        } else if (n == kHeaderLines && (f.empty() || f[0] != "DATA PERIODS")) {
            fail("{}:{}: expected the 'DATA PERIODS' header line, found '{}'", file, n,
                 f.empty() ? "" : f[0]);
        }
    }

    std::vector<WeatherRecord> records;
    int line_number = kHeaderLines;
    while (std::getline(in, line)) {
        ++line_number;
        if (line.empty() || line == "\r") continue;
        const auto f = detail::split_csv_line(line);
        const std::string where = fmt::format("{}:{}", file, line_number);
        if (f.size() < kEpwFields)
            fail("{}: {} fields, an EPW data line has {}", where, f.size(), kEpwFields);
        const FieldReader r{f, where};
        CivilTime c;
        c.year = year ? *year : r.integer(kYear, "year", 1, 9999);
        c.month = r.integer(kMonth, "month", 1, 12);
        c.day = r.integer(kDay, "day", 1, 31);
        const int hour = r.integer(kHour, "hour (EPW hours 1–24 end at the given hour)", 1, 24);
        const int minute = r.integer(kMinute, "minute", 0, 60);
        // Hour h covers (h−1):00–h:00; a minute of 0 or 60 marks the end of the hour (hourly
        // files).
        c.hour = hour - 1;
        c.utc_offset_h = site.utc_offset_h;
        double t = 0.0;
        try {
            t = to_unix_seconds(c) + ((minute <= 0 || minute >= 60) ? 3600.0 : minute * 60.0);
        } catch (const Error& e) {
            fail("{}: {}", where, e.what());
        }
        WeatherRecord w;
        w.time_s = t;
        w.air_temperature_c = r.required(kDryBulb, "dry bulb temperature", 99.9, -90.0, 70.0);
        w.dew_point_c = r.optional(kDewPoint, "dew point temperature", 99.9, -90.0, 70.0);
        w.relative_humidity_pct = r.optional(kRelHum, "relative humidity", 999.0, 0.0, 110.0);
        if (std::isnan(w.dew_point_c) && std::isnan(w.relative_humidity_pct))
            fail("{}: both dew point (99.9) and relative humidity (999) are missing; one is needed",
                 where);
        if (std::isnan(w.dew_point_c))
            w.dew_point_c = dew_point_c(w.air_temperature_c,
                                        std::max(0.1, std::min(100.0, w.relative_humidity_pct)));
        if (std::isnan(w.relative_humidity_pct))
            w.relative_humidity_pct = relative_humidity_pct(w.air_temperature_c, w.dew_point_c);
        w.pressure_pa =
            r.optional(kPressure, "atmospheric station pressure", 999999.0, 31000.0, 120000.0);
        if (std::isnan(w.pressure_pa)) w.pressure_pa = standard_pressure_pa(site.elevation_m);
        w.horizontal_ir_w_m2 = r.optional(kHorizontalIr, "horizontal infrared radiation intensity",
                                          9999.0, 0.0, 1000.0);
        w.global_horizontal_w_m2 =
            r.required(kGlobal, "global horizontal radiation", 9999.0, 0.0, 1500.0);
        w.direct_normal_w_m2 = r.required(kDirect, "direct normal radiation", 9999.0, 0.0, 1400.0);
        w.diffuse_horizontal_w_m2 =
            r.required(kDiffuse, "diffuse horizontal radiation", 9999.0, 0.0, 1000.0);
        w.wind_speed_m_s = r.required(kWindSpeed, "wind speed", 999.0, 0.0, 40.0);
        w.opaque_sky_cover_tenths =
            r.optional(kOpaqueSkyCover, "opaque sky cover", 99.0, 0.0, 10.0);
        if (std::isnan(w.horizontal_ir_w_m2) && std::isnan(w.opaque_sky_cover_tenths))
            fail(
                "{}: horizontal infrared radiation (9999) and opaque sky cover (99) are both "
                "missing; the sky "
                "longwave needs one of them",
                where);
        w.albedo = r.optional(kAlbedo, "albedo", 999.0, 0.0, 1.0);
        records.push_back(w);
    }
    if (records.size() < 2)
        fail("{}: needs at least two data lines, found {}", file, records.size());
    const double interval_s = records[1].time_s - records[0].time_s;
    return WeatherSeries(site, std::move(records), file, 0.5 * interval_s);
}

}  // namespace tirpol::thermal
