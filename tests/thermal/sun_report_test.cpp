// `tirpol sun`'s library side: the NREL SPA report's worked example (Reda & Andreas 2008, Table
// A5.2: zenith 50.11162°, azimuth 194.34024°, incidence 25.18700° on a 30° slope facing 170°)
// reached from a time written as text, the same instant written with and without its offset, and
// the times that are usage errors of --time.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tirpol/core/limits.h"
#include "tirpol/thermal/solar_position.h"

namespace tirpol::thermal {
namespace {

using ::testing::HasSubstr;

SunQuery golden(const std::string& time) {
    SunQuery q;
    q.spa.latitude_deg = 39.742476;
    q.spa.longitude_deg = -105.1786;
    q.spa.elevation_m = 1830.14;
    q.spa.pressure_mbar = 820.0;
    q.spa.temperature_c = 11.0;
    q.spa.delta_t_s = 67.0;
    q.time = time;
    q.tilt_deg = 30.0;
    q.surface_azimuth_deg = 170.0;
    return q;
}

TEST(SunReport, ReportWorkedExampleFromItsLocalTime) {
    const SunReport r = sun_report(golden("2003-10-17T12:30:30-07:00"));
    EXPECT_NEAR(r.position.zenith_deg, 50.11162, 1e-5);
    EXPECT_NEAR(r.position.azimuth_deg, 194.34024, 1e-5);
    EXPECT_NEAR(r.incidence_deg, 25.18700, 1e-5);
    EXPECT_NEAR(sun_report_json(r).at("zenith_deg").get<double>(), 50.11162, 1e-5);
    const std::string text = sun_report_text(r);
    EXPECT_THAT(text, HasSubstr("time (UTC)        2003-10-17T19:30:30+00:00"));
    EXPECT_THAT(text, HasSubstr("zenith              50.11162°"));
    EXPECT_THAT(text, HasSubstr("incidence           25.18700°  on a surface tilted 30.00° facing "
                                "azimuth 170.00°\n"));
    SunQuery no_offset = golden("2003-10-17T12:30:30");
    no_offset.utc_offset_h = -7.0;
    EXPECT_EQ(sun_report(no_offset).spa.unix_seconds, r.spa.unix_seconds);
}

TEST(SunReport, TimeWithoutOffsetOrNotATimeIsAnErrorOfTheTimeOption) {
    for (const char* bad : {"2003-10-17T12:30:30", "2003-10-17T25:00:00Z", "noon"}) {
        try {
            sun_report(golden(bad));
            FAIL() << bad;
        } catch (const OptionValueError& e) {
            EXPECT_EQ(e.option(), "--time") << bad;
        }
    }
}

}  // namespace
}  // namespace tirpol::thermal
