#include <algorithm>
#include <cmath>

#include "tirpol/core/error.h"
#include "tirpol/thermal/civil_time.h"
#include "tirpol/thermal/surface_temperature.h"

namespace tirpol::thermal {

WeatherSeries::WeatherSeries(Site site, std::vector<WeatherRecord> records, std::string source,
                             double radiation_lag_s)
    : m_site(std::move(site)),
      m_records(std::move(records)),
      m_source(std::move(source)),
      m_radiation_lag_s(radiation_lag_s) {
    if (m_records.size() < 2)
        fail("{}: weather needs at least two records, found {}", m_source, m_records.size());
    for (std::size_t i = 1; i < m_records.size(); ++i) {
        if (!(m_records[i].time_s > m_records[i - 1].time_s))
            fail("{}: record {} at {} is not after the previous one ({})", m_source, i + 1,
                 format_time(m_records[i].time_s, m_site.utc_offset_h),
                 format_time(m_records[i - 1].time_s, m_site.utc_offset_h));
    }
}

namespace {

double lerp(double a, double b, double f) {
    // A missing value on either side stays missing rather than being invented.
    if (std::isnan(a) || std::isnan(b)) return kMissing;
    return a + (b - a) * f;
}

// Index i and fraction f with time between records i and i+1 (clamped at the ends).
std::pair<std::size_t, double> bracket(const std::vector<WeatherRecord>& r, double t) {
    if (t <= r.front().time_s) return {0, 0.0};
    if (t >= r.back().time_s) return {r.size() - 2, 1.0};
    const auto it =
        std::upper_bound(r.begin(), r.end(), t,
                         [](double value, const WeatherRecord& rec) { return value < rec.time_s; });
    const auto i = static_cast<std::size_t>(it - r.begin()) - 1;
    return {i, (t - r[i].time_s) / (r[i + 1].time_s - r[i].time_s)};
}

}  // namespace

WeatherRecord WeatherSeries::at(double t) const {
    if (t < start_s() - 1e-6 || t > end_s() + 1e-6)
        fail("{}: no weather at {}; the file covers {} to {}", m_source,
             format_time(t, m_site.utc_offset_h), format_time(start_s(), m_site.utc_offset_h),
             format_time(end_s(), m_site.utc_offset_h));
    const auto [i, f] = bracket(m_records, t);
    const WeatherRecord& a = m_records[i];
    const WeatherRecord& b = m_records[i + 1];
    WeatherRecord out;
    out.time_s = t;
    out.air_temperature_c = lerp(a.air_temperature_c, b.air_temperature_c, f);
    out.dew_point_c = lerp(a.dew_point_c, b.dew_point_c, f);
    out.relative_humidity_pct = lerp(a.relative_humidity_pct, b.relative_humidity_pct, f);
    out.pressure_pa = lerp(a.pressure_pa, b.pressure_pa, f);
    out.wind_speed_m_s = lerp(a.wind_speed_m_s, b.wind_speed_m_s, f);
    out.opaque_sky_cover_tenths = lerp(a.opaque_sky_cover_tenths, b.opaque_sky_cover_tenths, f);
    out.albedo = lerp(a.albedo, b.albedo, f);
    // Radiation: values are interval averages, placed at the interval's middle.
    const auto [j, g] = bracket(m_records, t + m_radiation_lag_s);
    const WeatherRecord& c = m_records[j];
    const WeatherRecord& d = m_records[j + 1];
    out.global_horizontal_w_m2 = lerp(c.global_horizontal_w_m2, d.global_horizontal_w_m2, g);
    out.direct_normal_w_m2 = lerp(c.direct_normal_w_m2, d.direct_normal_w_m2, g);
    out.diffuse_horizontal_w_m2 = lerp(c.diffuse_horizontal_w_m2, d.diffuse_horizontal_w_m2, g);
    out.horizontal_ir_w_m2 = lerp(c.horizontal_ir_w_m2, d.horizontal_ir_w_m2, g);
    return out;
}

double standard_pressure_pa(double elevation_m) {
    return 101325.0 * std::pow(1.0 - 2.25577e-5 * elevation_m, 5.2559);
}

double erbs_diffuse_fraction(double kt) {
    if (kt <= 0.22) return 1.0 - 0.09 * kt;
    if (kt <= 0.80)
        return 0.9511 - 0.1604 * kt + 4.388 * kt * kt - 16.638 * kt * kt * kt +
               12.336 * kt * kt * kt * kt;
    return 0.165;
}

}  // namespace tirpol::thermal
