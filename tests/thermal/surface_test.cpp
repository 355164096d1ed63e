// The facet driver: solar geometry on facets, one sky for solver and renderer, spin-up, and the
// phenomenology the paper relies on (Gartley et al. §2.2.2, Fig. 2: in sun a dark ball is warmer
// than snow; under a clear night sky a horizontal surface cools below the air temperature).

#include <gtest/gtest.h>

#include <cmath>

#include "tirpol/core/error.h"
#include "tirpol/thermal/civil_time.h"
#include "tirpol/thermal/solar_position.h"
#include "tirpol/thermal/surface_temperature.h"

namespace tirpol::thermal {
namespace {

Site golden() { return {"Golden", 39.742476, -105.1786, -7.0, 1830.14}; }

// Three synthetic clear days in October: air 5–15 °C, solar from a clear-sky shape on the SPA sun.
WeatherSeries clear_days(double ir_w_m2 = kMissing) {
    std::vector<WeatherRecord> records;
    const double t0 = parse_time("2003-10-15T00:00", -7.0);
    for (int h = 0; h <= 24 * 3; ++h) {
        WeatherRecord r;
        r.time_s = t0 + h * 3600.0;
        const double local_h = std::fmod(h, 24.0);
        r.air_temperature_c = 10.0 + 5.0 * std::sin(2.0 * kPi * (local_h - 9.0) / 24.0);
        r.dew_point_c = -2.0;
        r.relative_humidity_pct = 40.0;
        r.pressure_pa = 82000.0;
        r.wind_speed_m_s = 1.0;
        SpaInput in;
        in.unix_seconds = r.time_s;
        in.latitude_deg = golden().latitude_deg;
        in.longitude_deg = golden().longitude_deg;
        in.elevation_m = golden().elevation_m;
        const double cz = std::cos(deg_to_rad(solar_position(in).zenith_deg));
        r.direct_normal_w_m2 = cz > 0.0 ? 900.0 * std::pow(cz, 0.3) : 0.0;
        r.diffuse_horizontal_w_m2 = cz > 0.0 ? 80.0 * cz : 0.0;
        r.global_horizontal_w_m2 =
            r.diffuse_horizontal_w_m2 + r.direct_normal_w_m2 * std::max(cz, 0.0);
        r.horizontal_ir_w_m2 = ir_w_m2;
        r.opaque_sky_cover_tenths = 0.0;
        records.push_back(r);
    }
    return WeatherSeries(golden(), records, "synthetic", 0.0);
}

ThermalMaterial rubber() {  // a dark ball shell: 5 mm rubber over air (adiabatic inside)
    ThermalMaterial m;
    m.name = "rubber";
    m.slab.layers = {{0.005, 0.16, 1100.0, 2000.0, 0}};
    m.solar_absorptivity = 0.9;
    m.thermal_emissivity = 0.95;
    return m;
}

ThermalMaterial snow() {  // 30 cm of snow on ground (snow properties: Incropera Table A.3)
    ThermalMaterial m;
    m.name = "snow";
    m.slab.layers = {{0.3, 0.11, 110.0, 2090.0, 0}};
    m.slab.back = {BackBoundary::Kind::FixedTemperature, 273.15, 0.0};
    m.solar_absorptivity = 0.2;
    m.thermal_emissivity = 0.98;
    return m;
}

TEST(ThermalSurface, HorizontalFacetReceivesGlobalIrradiance) {
    const WeatherSeries w = clear_days();
    const WeatherRecord r =
        w.at(parse_time("2003-10-16T12:00", -7.0));  // a record instant: GHI closes exactly
    ThermalOptions o;
    o.delta_t_s = 67.0;
    EXPECT_NEAR(facet_solar_irradiance_w_m2(r, w.site(), {0.0, 180.0}, o), r.global_horizontal_w_m2,
                0.5);
    // A north-facing wall at noon gets no direct sun, only diffuse + ground-reflected.
    const double north = facet_solar_irradiance_w_m2(r, w.site(), {90.0, 0.0}, o);
    EXPECT_NEAR(north, 0.5 * r.diffuse_horizontal_w_m2 + 0.5 * 0.2 * r.global_horizontal_w_m2,
                1e-9);
    // Full shadow removes exactly the direct beam.
    const double lit = facet_solar_irradiance_w_m2(r, w.site(), {0.0, 180.0}, o);
    const double shaded = facet_solar_irradiance_w_m2(r, w.site(), {0.0, 180.0}, o,
                                                      [](double, const Vec3&) { return 1.0; });
    EXPECT_NEAR(shaded, r.diffuse_horizontal_w_m2, 1e-9);
    EXPECT_GT(lit, 3.0 * shaded);
}

TEST(ThermalSurface, OneWeatherRecordDrivesSolverAndRendererSky) {
    const WeatherSeries w = clear_days(280.0);
    const WeatherRecord r = w.at(parse_time("2003-10-16T03:00", -7.0));
    const SkyRadianceModel sky = sky_from_weather(r, w.site(), ThermalOptions{});
    EXPECT_NEAR(sky.horizontal_irradiance_w_m2(), 280.0, 1e-9);  // measured IR is used as given
    const SurfaceForcing f = facet_forcing(r, w.site(), snow(), {0.0, 180.0}, ThermalOptions{});
    EXPECT_NEAR(f.incident_longwave_w_m2, 280.0, 1e-9);
    ThermalOptions model_only;
    model_only.use_measured_sky_ir = false;
    const SkyRadianceModel modelled = sky_from_weather(r, w.site(), model_only);
    EXPECT_NEAR(modelled.broadband_emissivity(),
                sky_emissivity(ClearSkyModel::BerdahlMartin1984,
                               {r.air_temperature_c, -2.0, 820.0,
                                local_solar_hour(r.time_s, w.site().longitude_deg), 0.0}),
                1e-12);
}

TEST(ThermalSurface, DarkBallIsWarmerThanSnowInSunAndSkyCoolsAtNight) {
    const WeatherSeries w = clear_days();
    ThermalOptions o;
    const Facet up{0.0, 180.0};
    const double noon = parse_time("2003-10-17T13:00", -7.0);
    const double night = parse_time("2003-10-17T04:00", -7.0);
    const double ball_noon = predict_surface_temperature(w, rubber(), up, noon, o);
    const double snow_noon = predict_surface_temperature(w, snow(), up, noon, o);
    EXPECT_GT(ball_noon, snow_noon + 10.0);
    EXPECT_GT(ball_noon, w.at(noon).air_temperature_c + kZeroCelsiusK);
    // Clear night: a thin sky-facing shell radiates below the air temperature.
    const double ball_night = predict_surface_temperature(w, rubber(), up, night, o);
    EXPECT_LT(ball_night, w.at(night).air_temperature_c + kZeroCelsiusK - 2.0);
}

TEST(ThermalSurface, SpinUpForgetsTheInitialState) {
    const WeatherSeries w = clear_days();
    const double t = parse_time("2003-10-17T15:00", -7.0);
    ThermalOptions a, b;
    a.spin_up_hours = 36.0;
    b.spin_up_hours = 60.0;
    EXPECT_NEAR(predict_surface_temperature(w, rubber(), {30.0, 200.0}, t, a),
                predict_surface_temperature(w, rubber(), {30.0, 200.0}, t, b), 0.01);
    ThermalOptions too_long;
    too_long.spin_up_hours = 24.0 * 5;
    EXPECT_THROW(predict_surface_temperature(w, rubber(), {0.0, 180.0}, t, too_long), Error);
}

TEST(ThermalSurface, SimulatedHistoryIsSampledOnRequestedGrid) {
    const WeatherSeries w = clear_days();
    const double end = parse_time("2003-10-17T12:00", -7.0);
    const auto s = simulate_facet(w, rubber(), {0.0, 180.0}, end - 48 * 3600.0, end,
                                  end - 24 * 3600.0, 3600.0, ThermalOptions{});
    ASSERT_EQ(s.size(), 25u);
    EXPECT_DOUBLE_EQ(s.front().time_s, end - 24 * 3600.0);
    EXPECT_DOUBLE_EQ(s.back().time_s, end);
    // The surface balance closes within the conduction term: net flux stays bounded for a thin
    // shell.
    for (const auto& x : s) EXPECT_LT(std::abs(x.fluxes.net()), 60.0);
}

TEST(ThermalSurface, BatchedFacetsMatchOneAtATime) {
    const WeatherSeries w = clear_days();
    const double t = parse_time("2003-10-17T10:00", -7.0);
    const ThermalMaterial a = rubber(), b = snow();
    const ShadowFunction half = [](double, const Vec3&) { return 0.5; };
    const std::vector<FacetRequest> requests = {
        {&a, {0.0, 180.0}, {}}, {&b, {60.0, 120.0}, half}, {&a, {90.0, 270.0}, {}}};
    const auto batch = predict_surface_temperatures(w, requests, t, ThermalOptions{});
    ASSERT_EQ(batch.size(), 3u);
    for (std::size_t k = 0; k < requests.size(); ++k)
        EXPECT_DOUBLE_EQ(batch[k],
                         predict_surface_temperature(w, *requests[k].material, requests[k].facet, t,
                                                     ThermalOptions{}, requests[k].shadow));
}

}  // namespace
}  // namespace tirpol::thermal
