#pragma once
/// \file weather.h
/// Weather that drives the surface temperatures and the sky: EnergyPlus EPW files and a simple CSV
/// for field logs (docs/thermal.md describes both), held as a time series of records with linear
/// interpolation in time.

#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace tirpol::thermal {

/// Where the weather (and the scene) is.
struct Site {
    std::string name;
    double latitude_deg = 0.0;   ///< north positive
    double longitude_deg = 0.0;  ///< east positive
    double utc_offset_h = 0.0;   ///< standard time zone, hours (UTC−7 → −7)
    double elevation_m = 0.0;
};

inline constexpr double kMissing = std::numeric_limits<double>::quiet_NaN();

/// One weather observation. State variables (temperature, humidity, pressure, wind, sky cover) are
/// instantaneous at `time_s`; radiation fields are averages over the interval that, for EPW files,
/// ends at `time_s` (WeatherSeries::at accounts for that).
struct WeatherRecord {
    double time_s = 0.0;  ///< UTC seconds since 1970 (civil_time.h)
    double air_temperature_c = 0.0;
    double dew_point_c = 0.0;
    double relative_humidity_pct = 0.0;
    double pressure_pa = 101325.0;
    double wind_speed_m_s = 0.0;
    double global_horizontal_w_m2 = 0.0;   ///< GHI
    double direct_normal_w_m2 = 0.0;       ///< DNI
    double diffuse_horizontal_w_m2 = 0.0;  ///< DHI
    double horizontal_ir_w_m2 =
        kMissing;  ///< measured downwelling longwave on a horizontal surface, or NaN
    double opaque_sky_cover_tenths = kMissing;  ///< 0–10, or NaN
    double albedo = kMissing;                   ///< ground solar reflectance, or NaN
};

/// A time-ordered series of records from one file.
class WeatherSeries {
public:
    /// `radiation_lag_s`: radiation fields of a record describe the interval ending at its time;
    /// they are interpolated as if observed `radiation_lag_s` earlier (half the interval for EPW, 0
    /// for instantaneous field logs). Throws tirpol::Error if fewer than two records or times not
    /// increasing.
    WeatherSeries(Site site, std::vector<WeatherRecord> records, std::string source,
                  double radiation_lag_s);

    const Site& site() const { return m_site; }
    const std::vector<WeatherRecord>& records() const { return m_records; }
    const std::string& source() const { return m_source; }
    double start_s() const { return m_records.front().time_s; }
    double end_s() const { return m_records.back().time_s; }

    /// The weather at instant `time_s`, linearly interpolated (radiation on its own, lagged, time
    /// axis). Throws tirpol::Error naming the file and its time span when `time_s` is outside it.
    WeatherRecord at(double time_s) const;

private:
    Site m_site;
    std::vector<WeatherRecord> m_records;
    std::string m_source;
    double m_radiation_lag_s;
};

/// Reads an EnergyPlus weather file (EnergyPlus Auxiliary Programs, "Weather Converter Program":
/// 8 header lines, LOCATION first; data lines of 35 fields; hour 1–24 is the hour ending at that
/// time, local standard time). Missing-value codes: dry bulb 99.9, wind 999 and the three solar
/// fields 9999 are errors; dew point 99.9 / relative humidity 999 are derived one from the other;
/// pressure 999999 → standard atmosphere at the site elevation; horizontal IR 9999, opaque sky
/// cover 99 and albedo 999 → missing (at least one of horizontal IR or opaque sky cover must be
/// present). `year`: put every record in this year (typical-year files mix years).
WeatherSeries load_epw(const std::filesystem::path& path, std::optional<int> year = std::nullopt);

/// Reads a field-log CSV (docs/thermal.md): columns `time` (ISO 8601; without an offset the site's
/// UTC offset applies), `air_temperature_c`, `relative_humidity_pct` or `dew_point_c`,
/// `wind_speed_m_s`, `global_horizontal_w_m2`; optional `direct_normal_w_m2` and
/// `diffuse_horizontal_w_m2` (both or neither; when absent GHI is split with Erbs et al. 1982),
/// `sky_ir_w_m2`, `pressure_pa`, `opaque_sky_cover_tenths`. Values are instantaneous. Errors name
/// the file, line and column: missing required columns or cells, times not increasing, gaps longer
/// than `max_gap_h`, out-of-range values.
WeatherSeries load_weather_csv(const std::filesystem::path& path, const Site& site,
                               double max_gap_h = 3.0);

/// Standard-atmosphere pressure (Pa) at `elevation_m` (ASHRAE Handbook—Fundamentals ch. 1, eq. 3).
double standard_pressure_pa(double elevation_m);

/// Diffuse fraction of global horizontal irradiance from the clearness index k_t (Erbs, Klein &
/// Duffie, Solar Energy 28 (1982) 293–302, hourly correlation).
double erbs_diffuse_fraction(double clearness_index);

}  // namespace tirpol::thermal
