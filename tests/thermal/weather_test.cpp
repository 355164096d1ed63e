// Weather input: an EPW file written here with known values (layout per the EnergyPlus Auxiliary
// Programs manual, "EnergyPlus Weather File (EPW) Data Dictionary": 8 header lines, 35 fields a
// line, hour h = the hour ending at h:00 local standard time, missing
// codes 99.9/999/9999/999999/99) and the field-log CSV of docs/thermal.md.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "test_support.h"
#include "tirpol/core/error.h"
#include "tirpol/thermal/civil_time.h"
#include "tirpol/thermal/surface_temperature.h"

namespace tirpol::thermal {
namespace {

using ::testing::HasSubstr;

const char* kHeader =
    "LOCATION,Golden,CO,USA,TEST,724666,39.74,-105.18,-7.0,1829.0\n"
    "DESIGN CONDITIONS,0\n"
    "TYPICAL/EXTREME PERIODS,0\n"
    "GROUND TEMPERATURES,0\n"
    "HOLIDAYS/DAYLIGHT SAVINGS,No,0,0,0\n"
    "COMMENTS 1,written by thermal_weather_test\n"
    "COMMENTS 2,\n"
    "DATA PERIODS,1,1,Data,Sunday, 1/ 1,12/31\n";

struct EpwHour {
    int day, hour;
    double dry = 10, dew = 0, rh = 50, pressure = 81000, ir = 250, ghi = 0, dni = 0, dhi = 0,
           wind = 2, opaque = 3;
};

std::string epw_line(const EpwHour& h) {
    std::ostringstream s;
    s << "2021,1," << h.day << ',' << h.hour
      << ",60,?9?9?9?9E0?9?9?9?9?9?9?9?9?9?9?9?9?9?9?9*9*9?9?9?9," << h.dry << ',' << h.dew << ','
      << h.rh << ',' << h.pressure << ",0,1415," << h.ir << ',' << h.ghi << ',' << h.dni << ','
      << h.dhi << ",0,0,0,0,180," << h.wind << ",5," << h.opaque
      << ",9999,77777,9,999999999,10,0.1,0,88,0.2,0,0";
    return s.str();
}

std::string epw_text(std::vector<EpwHour> hours) {
    std::string text = kHeader;
    for (const auto& h : hours) text += epw_line(h) + "\n";
    return text;
}

std::vector<EpwHour> two_days() {
    std::vector<EpwHour> hours;
    for (int d = 1; d <= 2; ++d)
        for (int h = 1; h <= 24; ++h) {
            EpwHour e{d, h};
            e.dry = h;  // dry bulb = hour number: easy to check interpolation
            e.ghi = (h >= 9 && h <= 16) ? 50.0 * h : 0.0;
            e.dni = e.ghi;
            e.dhi = 0.1 * e.ghi;
            hours.push_back(e);
        }
    return hours;
}

TEST(WeatherEpw, ReadsHeaderFieldsAndHourEndingTimes) {
    test::TempDir dir;
    test::write_text(dir / "w.epw", epw_text(two_days()));
    const WeatherSeries w = load_epw(dir / "w.epw");
    EXPECT_EQ(w.site().name, "Golden");
    EXPECT_DOUBLE_EQ(w.site().latitude_deg, 39.74);
    EXPECT_DOUBLE_EQ(w.site().longitude_deg, -105.18);
    EXPECT_DOUBLE_EQ(w.site().utc_offset_h, -7.0);
    ASSERT_EQ(w.records().size(), 48u);
    // Hour 1 of Jan 1 ends at 01:00 local standard time; hour 24 ends at midnight of Jan 2.
    EXPECT_DOUBLE_EQ(w.records()[0].time_s, parse_time("2021-01-01T01:00-07:00", 0.0));
    EXPECT_DOUBLE_EQ(w.records()[23].time_s, parse_time("2021-01-02T00:00-07:00", 0.0));
    EXPECT_DOUBLE_EQ(w.records()[0].wind_speed_m_s, 2.0);
    EXPECT_DOUBLE_EQ(w.records()[0].horizontal_ir_w_m2, 250.0);
    EXPECT_DOUBLE_EQ(w.records()[0].opaque_sky_cover_tenths, 3.0);
    EXPECT_DOUBLE_EQ(w.records()[0].albedo, 0.2);
}

TEST(WeatherEpw, InterpolatesStateAtInstantsAndRadiationAtHourMiddles) {
    test::TempDir dir;
    test::write_text(dir / "w.epw", epw_text(two_days()));
    const WeatherSeries w = load_epw(dir / "w.epw");
    // Temperature: instantaneous at the hour's end → 10:30 lies halfway between hours 10 and 11.
    EXPECT_NEAR(w.at(parse_time("2021-01-01T10:30", -7.0)).air_temperature_c, 10.5, 1e-9);
    // Radiation: the hour-12 value (600 W/m²) is the 11:00–12:00 average, placed at 11:30.
    EXPECT_NEAR(w.at(parse_time("2021-01-01T11:30", -7.0)).global_horizontal_w_m2, 600.0, 1e-9);
    EXPECT_NEAR(w.at(parse_time("2021-01-01T12:00", -7.0)).global_horizontal_w_m2, 625.0, 1e-9);
    EXPECT_THAT([&] { w.at(parse_time("2021-01-05T12:00", -7.0)); },
                ::testing::ThrowsMessage<Error>(HasSubstr("covers")));
}

TEST(WeatherEpw, MissingValueCodesGiveErrorsOrDocumentedFallbacks) {
    test::TempDir dir;
    auto load_with = [&](auto edit) {
        auto hours = two_days();
        edit(hours[5]);
        test::write_text(dir / "m.epw", epw_text(hours));
        return load_epw(dir / "m.epw");
    };
    // Dry bulb 99.9: error naming the line (header 8 lines + 6th record = line 14) and the field.
    EXPECT_THAT(
        [&] { load_with([](EpwHour& h) { h.dry = 99.9; }); },
        ::testing::ThrowsMessage<Error>(AllOf(HasSubstr("m.epw:14"), HasSubstr("dry bulb"))));
    EXPECT_THAT([&] { load_with([](EpwHour& h) { h.ghi = 9999; }); },
                ::testing::ThrowsMessage<Error>(HasSubstr("global horizontal")));
    EXPECT_THAT([&] { load_with([](EpwHour& h) { h.wind = 999; }); },
                ::testing::ThrowsMessage<Error>(HasSubstr("wind speed")));
    EXPECT_THAT(
        [&] {
            load_with([](EpwHour& h) {
                h.ir = 9999;
                h.opaque = 99;
            });
        },
        ::testing::ThrowsMessage<Error>(HasSubstr("both missing")));
    EXPECT_THAT([&] { load_with([](EpwHour& h) { h.wind = 75; }); },
                ::testing::ThrowsMessage<Error>(HasSubstr("plausible range")));
    // Horizontal IR 9999 alone → missing (the sky model takes over); pressure 999999 → standard
    // atmosphere at 1829 m (≈ 81.2 kPa); dew point 99.9 → from relative humidity.
    const WeatherSeries w = load_with([](EpwHour& h) {
        h.ir = 9999;
        h.pressure = 999999;
        h.dew = 99.9;
        h.dry = 20;
    });
    EXPECT_TRUE(std::isnan(w.records()[5].horizontal_ir_w_m2));
    EXPECT_NEAR(w.records()[5].pressure_pa, 81200.0, 100.0);
    EXPECT_NEAR(w.records()[5].dew_point_c, 9.26, 0.02);  // 20 °C at 50 %
    // Too few fields.
    std::string text = epw_text(two_days());
    text += "2021,1,3,1,60,x,1,2,3\n";
    test::write_text(dir / "short.epw", text);
    EXPECT_THAT([&] { load_epw(dir / "short.epw"); },
                ::testing::ThrowsMessage<Error>(HasSubstr("35")));
    test::write_text(dir / "nohdr.epw", epw_line({1, 1}) + "\n");
    EXPECT_THAT([&] { load_epw(dir / "nohdr.epw"); },
                ::testing::ThrowsMessage<Error>(HasSubstr("LOCATION")));
}

TEST(WeatherEpw, YearOverrideMapsTypicalYearFiles) {
    test::TempDir dir;
    test::write_text(dir / "w.epw", epw_text(two_days()));
    const WeatherSeries w = load_epw(dir / "w.epw", 2026);
    EXPECT_DOUBLE_EQ(w.start_s(), parse_time("2026-01-01T01:00-07:00", 0.0));
}

Site golden() { return {"Golden", 39.742476, -105.1786, -7.0, 1830.14}; }

TEST(WeatherCsv, ReadsFieldLogAndSplitsGlobalWithErbs) {
    test::TempDir dir;
    test::write_text(dir / "log.csv",
                     "# field log\n"
                     "time,air_temperature_c,relative_humidity_pct,wind_speed_m_s,global_"
                     "horizontal_w_m2,opaque_sky_cover_tenths\n"
                     "2003-10-17T11:30,12.0,40,1.5,600,0\n"
                     "2003-10-17T12:30:30,13.0,38,2.0,650,0\n"
                     "2003-10-17T13:30,13.5,35,2.5,600,1\n");
    const WeatherSeries w = load_weather_csv(dir / "log.csv", golden());
    ASSERT_EQ(w.records().size(), 3u);
    const WeatherRecord& r = w.records()[1];
    EXPECT_DOUBLE_EQ(r.time_s, parse_time("2003-10-17T12:30:30-07:00", 0.0));
    // Closure: GHI = DHI + DNI cos z with the SPA zenith (50.11° here, the report's example
    // instant).
    EXPECT_NEAR(r.diffuse_horizontal_w_m2 +
                    r.direct_normal_w_m2 * std::cos(50.1116 * 3.14159265358979 / 180.0),
                650.0, 0.05);
    EXPECT_GT(r.direct_normal_w_m2, r.diffuse_horizontal_w_m2);  // a clear day (k_t ≈ 0.73)
    EXPECT_NEAR(r.pressure_pa, standard_pressure_pa(1830.14), 1e-9);
}

TEST(WeatherCsv, ClearErrorsForBadLogs) {
    test::TempDir dir;
    const std::string header =
        "time,air_temperature_c,relative_humidity_pct,wind_speed_m_s,global_horizontal_w_m2,sky_ir_"
        "w_m2\n";
    test::write_text(
        dir / "gap.csv",
        header + "2021-05-01T10:00,10,50,1,100,300\n2021-05-01T16:00,11,50,1,100,300\n");
    EXPECT_THAT([&] { load_weather_csv(dir / "gap.csv", golden()); },
                ::testing::ThrowsMessage<Error>(HasSubstr("gap")));
    test::write_text(
        dir / "order.csv",
        header + "2021-05-01T10:00,10,50,1,100,300\n2021-05-01T09:00,11,50,1,100,300\n");
    EXPECT_THAT([&] { load_weather_csv(dir / "order.csv", golden()); },
                ::testing::ThrowsMessage<Error>(HasSubstr("not after")));
    test::write_text(dir / "typo.csv", "time,air_temprature_c\n");
    EXPECT_THAT([&] { load_weather_csv(dir / "typo.csv", golden()); },
                ::testing::ThrowsMessage<Error>(HasSubstr("did you mean 'air_temperature_c'")));
    test::write_text(dir / "nosky.csv",
                     "time,air_temperature_c,dew_point_c,wind_speed_m_s,global_horizontal_w_m2\n");
    EXPECT_THAT([&] { load_weather_csv(dir / "nosky.csv", golden()); },
                ::testing::ThrowsMessage<Error>(HasSubstr("sky_ir_w_m2")));
    test::write_text(
        dir / "range.csv",
        header + "2021-05-01T10:00,10,50,1,2000,300\n2021-05-01T11:00,11,50,1,100,300\n");
    EXPECT_THAT([&] { load_weather_csv(dir / "range.csv", golden()); },
                ::testing::ThrowsMessage<Error>(
                    AllOf(HasSubstr("range.csv:2"), HasSubstr("global_horizontal_w_m2"))));
}

TEST(WeatherCsv, ErbsCorrelationValues) {
    // Erbs, Klein & Duffie (1982): 1 − 0.09 k_t below 0.22, 0.165 above 0.8, continuous in between.
    EXPECT_DOUBLE_EQ(erbs_diffuse_fraction(0.1), 0.991);
    EXPECT_DOUBLE_EQ(erbs_diffuse_fraction(0.9), 0.165);
    EXPECT_NEAR(erbs_diffuse_fraction(0.22), 1.0 - 0.09 * 0.22, 2e-3);
    EXPECT_NEAR(erbs_diffuse_fraction(0.80), 0.165, 2e-3);
}

}  // namespace
}  // namespace tirpol::thermal
