// SPA against the worked example of Reda & Andreas, NREL/TP-560-34302 (2003, rev. 2008), Table
// A5.2: 2003-10-17 12:30:30 local (UTC−7), 39.742476° N, 105.1786° W, 1830.14 m, 820 mbar, 11 °C,
// ΔT = 67 s, ΔUT1 = 0. The report prints (and NREL's spa_tester.c reproduces): JD 2452930.312847,
// L 24.0182616917°, B −0.0001011219°, R 0.9965422974 AU, Δψ −0.00399840°, Δε 0.00166657°,
// ε 23.440465°, H 11.105902°, zenith 50.11162°, azimuth 194.34024°, incidence 25.18700° (slope 30°,
// azimuth rotation −10° from south).

#include "tirpol/thermal/solar_position.h"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "tirpol/core/error.h"
#include "tirpol/thermal/civil_time.h"

namespace tirpol::thermal {
namespace {

SpaInput report_example() {
    SpaInput in;
    in.unix_seconds = to_unix_seconds({2003, 10, 17, 12, 30, 30.0, -7.0});
    in.latitude_deg = 39.742476;
    in.longitude_deg = -105.1786;
    in.elevation_m = 1830.14;
    in.pressure_mbar = 820.0;
    in.temperature_c = 11.0;
    in.delta_t_s = 67.0;
    in.delta_ut1_s = 0.0;
    in.atmospheric_refraction_deg = 0.5667;
    return in;
}

TEST(SolarPosition, ReproducesReportWorkedExampleIntermediates) {
    const SolarPosition s = solar_position(report_example());
    EXPECT_NEAR(s.julian_day, 2452930.312847, 1e-6);
    EXPECT_NEAR(s.heliocentric_longitude_deg, 24.0182616917, 1e-9);
    EXPECT_NEAR(s.heliocentric_latitude_deg, -0.0001011219, 1e-10);
    EXPECT_NEAR(s.earth_radius_au, 0.9965422974, 1e-10);
    EXPECT_NEAR(s.nutation_longitude_deg, -0.00399840, 1e-8);
    EXPECT_NEAR(s.nutation_obliquity_deg, 0.00166657, 1e-8);
    EXPECT_NEAR(s.true_obliquity_deg, 23.440465, 1e-6);
    EXPECT_NEAR(s.hour_angle_deg, 11.105902, 1e-6);
}

TEST(SolarPosition, ReproducesReportZenithAndAzimuthTo1e5Degrees) {
    const SolarPosition s = solar_position(report_example());
    EXPECT_NEAR(s.zenith_deg, 50.11162, 1e-5);
    EXPECT_NEAR(s.azimuth_deg, 194.34024, 1e-5);
}

TEST(SolarPosition, ReproducesReportIncidenceOnTiltedSurface) {
    // Report: slope 30°, surface azimuth rotation −10° (east of south) → 170° from north.
    const SolarPosition s = solar_position(report_example());
    EXPECT_NEAR(incidence_angle_deg(s, 30.0, 170.0), 25.18700, 1e-5);
}

TEST(SolarPosition, JsonCarriesTheReportsWorkedExample) {
    // The keys of `tirpol sun --json` (docs/thermal.md) with the report's values (Table A5.2) and
    // its incidence on the 30° slope facing 170°.
    const SpaInput in = report_example();
    const nlohmann::json out = solar_position_json(in, solar_position(in), 30.0, 170.0);
    EXPECT_EQ(out.at("time_utc").get<std::string>(), format_time(in.unix_seconds, 0.0));
    EXPECT_EQ(out.at("time_utc").get<std::string>().substr(0, 19), "2003-10-17T19:30:30");
    EXPECT_NEAR(out.at("julian_day").get<double>(), 2452930.312847, 1e-6);
    EXPECT_NEAR(out.at("zenith_deg").get<double>(), 50.11162, 1e-5);
    EXPECT_NEAR(out.at("elevation_deg").get<double>(), 90.0 - 50.11162, 1e-5);
    EXPECT_NEAR(out.at("azimuth_deg").get<double>(), 194.34024, 1e-5);
    EXPECT_NEAR(out.at("earth_sun_distance_au").get<double>(), 0.9965422974, 1e-10);
    EXPECT_NEAR(out.at("hour_angle_deg").get<double>(), 11.105902, 1e-6);
    EXPECT_DOUBLE_EQ(out.at("surface").at("tilt_deg").get<double>(), 30.0);
    EXPECT_DOUBLE_EQ(out.at("surface").at("azimuth_deg").get<double>(), 170.0);
    EXPECT_NEAR(out.at("surface").at("incidence_deg").get<double>(), 25.18700, 1e-5);
}

TEST(SolarPosition, IncidenceMatchesAngleBetweenSunAndNormalVectors) {
    const SolarPosition s = solar_position(report_example());
    for (double tilt : {0.0, 35.0, 90.0, 150.0}) {
        for (double az : {0.0, 100.0, 250.0}) {
            const double dot = sun_direction(s).dot(facet_normal(tilt, az));
            EXPECT_NEAR(incidence_angle_deg(s, tilt, az), rad_to_deg(std::acos(dot)), 1e-9);
        }
    }
    EXPECT_NEAR(incidence_angle_deg(s, 0.0, 0.0), s.zenith_deg, 1e-12);
}

TEST(SolarPosition, SunIsLowestAtLocalMidnightAndDeclinationFollowsSeasons) {
    // Equinox-to-solstice sanity (Meeus, Astronomical Algorithms ch. 25): |δ| ≤ 23.44°, δ ≈ +23.44°
    // at the June solstice; at local solar noon on the equator at an equinox the sun is near the
    // zenith.
    SpaInput in = report_example();
    in.unix_seconds = parse_time("2021-06-21T03:32:00Z", 0.0);
    const SolarPosition june = solar_position(in);
    EXPECT_NEAR(june.declination_deg, 23.4366, 2e-3);
    in.latitude_deg = 0.0;
    in.longitude_deg = 0.0;
    in.elevation_m = 0.0;
    in.unix_seconds = parse_time("2021-03-20T12:07:00Z", 0.0);
    EXPECT_LT(solar_position(in).zenith_deg, 0.5);
}

TEST(SolarPosition, RejectsOutOfRangeInputs) {
    SpaInput in = report_example();
    in.latitude_deg = 91.0;
    EXPECT_THROW(solar_position(in), Error);
    in = report_example();
    in.longitude_deg = -200.0;
    EXPECT_THROW(solar_position(in), Error);
}

TEST(CivilTime, RoundTripsAndParsesOffsets) {
    const double t = parse_time("2003-10-17T12:30:30-07:00", 0.0);
    EXPECT_DOUBLE_EQ(t, parse_time("2003-10-17 19:30:30Z", 5.0));
    EXPECT_DOUBLE_EQ(t, parse_time("2003-10-17T12:30:30", -7.0));
    EXPECT_EQ(format_time(t, -7.0), "2003-10-17T12:30:30-07:00");
    EXPECT_DOUBLE_EQ(to_unix_seconds({1970, 1, 1, 0, 0, 0.0, 0.0}), 0.0);
    EXPECT_DOUBLE_EQ(julian_day(0.0), 2440587.5);  // 1970-01-01T00:00 UT
    EXPECT_DOUBLE_EQ(to_unix_seconds({2000, 2, 29, 24, 0, 0.0, 0.0}),
                     to_unix_seconds({2000, 3, 1, 0, 0, 0.0, 0.0}));
    EXPECT_THROW(parse_time("2003-02-29T00:00", 0.0), Error);
    EXPECT_THROW(parse_time("yesterday", 0.0), Error);
    EXPECT_THROW(parse_time("2003-10-17T12:30:30+0", 0.0), Error);
}

}  // namespace
}  // namespace tirpol::thermal
