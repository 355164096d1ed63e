// Sky longwave models. Coefficients as published: Berdahl & Martin, Solar Energy 32 (1984) 663;
// Brutsaert, Water Resour. Res. 11 (1975) 742; Clark & Allen (1978) with the cloud factor of the
// EnergyPlus Engineering Reference ("Sky Radiation Modeling"); Idso, Water Resour. Res. 17 (1981)
// 295. The angular law is Granqvist & Hjortsberg, J. Appl. Phys. 52 (1981) 4205, whose
// hemispherical integral is the plane-parallel slab result 1 − 2E₃(τ) (E₃ values: Abramowitz &
// Stegun Table 5.1).

#include <gtest/gtest.h>

#include <cmath>

#include "tirpol/core/error.h"
#include "tirpol/core/geometry.h"
#include "tirpol/thermal/sky_longwave.h"

namespace tirpol::thermal {
namespace {

SkyConditions typical() {
    SkyConditions c;
    c.air_temperature_c = 20.0;
    c.dew_point_c = 10.0;
    c.pressure_hpa = 1000.0;
    c.local_solar_hour = 6.0;  // cos(2π·6/24) = 0: no diurnal term
    return c;
}

TEST(SkyLongwave, ModelsEvaluateTheirPublishedFormulas) {
    const SkyConditions c = typical();
    // Berdahl & Martin (1984): 0.711 + 0.56·0.1 + 0.73·0.01 at T_dp = 10 °C.
    EXPECT_NEAR(clear_sky_emissivity(ClearSkyModel::BerdahlMartin1984, c), 0.7743, 1e-12);
    // Vapour pressure at a 10 °C dew point: 12.27 hPa (Magnus/Alduchov–Eskridge; WMO tables
    // give 12.28).
    const double e = saturation_vapour_pressure_hpa(10.0);
    EXPECT_NEAR(e, 12.27, 0.01);
    EXPECT_NEAR(clear_sky_emissivity(ClearSkyModel::Brutsaert1975, c),
                1.24 * std::pow(e / 293.15, 1.0 / 7.0), 1e-12);
    EXPECT_NEAR(clear_sky_emissivity(ClearSkyModel::ClarkAllen1978, c),
                0.787 + 0.764 * std::log(283.15 / 273.0), 1e-12);
    EXPECT_NEAR(clear_sky_emissivity(ClearSkyModel::Idso1981, c),
                0.70 + 5.95e-5 * e * std::exp(1500.0 / 293.15), 1e-12);
    // Berdahl–Martin diurnal (+0.013 at midnight) and pressure (+0.00012 per hPa above 1000) terms.
    SkyConditions night = c;
    night.local_solar_hour = 0.0;
    night.pressure_hpa = 1010.0;
    EXPECT_NEAR(clear_sky_emissivity(ClearSkyModel::BerdahlMartin1984, night),
                0.7743 + 0.013 + 0.0012, 1e-12);
}

TEST(SkyLongwave, EmpiricalModelsAgreeForTypicalConditionsAndRiseWithHumidity) {
    // The four correlations were fitted to different data sets but agree within a few hundredths
    // for a mild humid day (Flerchinger et al., Water Resour. Res. 45 (2009) W03423, compare them
    // at large).
    const SkyConditions c = typical();
    for (auto m : {ClearSkyModel::BerdahlMartin1984, ClearSkyModel::Brutsaert1975,
                   ClearSkyModel::ClarkAllen1978, ClearSkyModel::Idso1981}) {
        const double eps = clear_sky_emissivity(m, c);
        EXPECT_GT(eps, 0.74) << to_string(m);
        EXPECT_LT(eps, 0.84) << to_string(m);
        SkyConditions dry = c;
        dry.dew_point_c = -10.0;
        EXPECT_LT(clear_sky_emissivity(m, dry), eps) << to_string(m);
        EXPECT_EQ(parse_clear_sky_model(to_string(m)), m);
    }
    EXPECT_THROW(parse_clear_sky_model("brutseart"), Error);
}

TEST(SkyLongwave, CloudFactorAndWindowEmissivity) {
    EXPECT_DOUBLE_EQ(clark_allen_cloud_factor(0.0), 1.0);
    EXPECT_NEAR(clark_allen_cloud_factor(10.0), 1.0 + 0.224 - 0.35 + 0.28, 1e-12);
    SkyConditions c = typical();
    const double clear_window = window_sky_emissivity(c);
    // The 8–14 µm window is far more transparent than the broadband sky.
    EXPECT_LT(clear_window, clear_sky_emissivity(ClearSkyModel::BerdahlMartin1984, c) - 0.2);
    c.opaque_sky_cover_tenths = 10.0;
    EXPECT_DOUBLE_EQ(window_sky_emissivity(c), 1.0);  // overcast: black clouds at air temperature
    EXPECT_LE(sky_emissivity(ClearSkyModel::ClarkAllen1978, c), 1.0);
}

TEST(SkyLongwave, DewPointRoundTripsAndMatchesTables) {
    // 20 °C at 50 % RH has a dew point of 9.3 °C (psychrometric tables).
    EXPECT_NEAR(dew_point_c(20.0, 50.0), 9.26, 0.02);
    for (double t : {-10.0, 5.0, 30.0})
        for (double rh : {20.0, 60.0, 100.0})
            EXPECT_NEAR(relative_humidity_pct(t, dew_point_c(t, rh)), rh, 1e-9);
    EXPECT_THROW(dew_point_c(20.0, 0.0), Error);
}

TEST(SkyLongwave, AngularLawIntegratesToSlabEmissivity) {
    // τ = 1 → ε_zenith = 1 − e⁻¹ and ε_hemispherical = 1 − 2E₃(1) = 1 − 2·0.109692 (A&S Table 5.1).
    EXPECT_NEAR(hemispherical_from_zenith_emissivity(1.0 - std::exp(-1.0)), 1.0 - 2.0 * 0.1096920,
                1e-6);
    // Independent check by midpoint quadrature of 2∫ε(θ) cosθ sinθ dθ.
    for (double ez : {0.05, 0.3, 0.7, 0.95}) {
        double sum = 0.0;
        const int n = 20000;
        for (int i = 0; i < n; ++i) {
            const double th = (i + 0.5) * (kPi / 2) / n;
            sum += directional_sky_emissivity(ez, rad_to_deg(th)) * std::cos(th) * std::sin(th) *
                   (kPi / 2) / n;
        }
        EXPECT_NEAR(hemispherical_from_zenith_emissivity(ez), 2.0 * sum, 1e-7) << ez;
        EXPECT_NEAR(zenith_from_hemispherical_emissivity(hemispherical_from_zenith_emissivity(ez)),
                    ez, 1e-9);
    }
    // Emissivity grows from zenith to horizon and the horizon is black.
    EXPECT_LT(directional_sky_emissivity(0.3, 0.0), directional_sky_emissivity(0.3, 60.0));
    EXPECT_NEAR(directional_sky_emissivity(0.3, 0.0), 0.3, 1e-15);
    EXPECT_DOUBLE_EQ(directional_sky_emissivity(0.3, 90.0), 1.0);
}

TEST(SkyLongwave, RadianceModelIntegratesToIrradianceAndStaysBelowAirBlackbody) {
    const SkyRadianceModel sky(290.0, 0.78, 0.35);
    double sum = 0.0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        const double th = (i + 0.5) * (kPi / 2) / n;
        sum += sky.broadband_radiance(rad_to_deg(th)) * std::cos(th) * std::sin(th) * 2.0 * kPi *
               (kPi / 2) / n;
    }
    EXPECT_NEAR(sum, sky.horizontal_irradiance_w_m2(), 1e-4 * sum);
    EXPECT_NEAR(sky.horizontal_irradiance_w_m2(), 0.78 * kStefanBoltzmann * std::pow(290.0, 4),
                1e-9);
    const Band lwir(8.0, 14.0);
    EXPECT_LT(sky.band_radiance(lwir, 0.0), 0.5 * lwir.radiance(290.0));
    EXPECT_LT(sky.band_radiance(lwir, 0.0), sky.band_radiance(lwir, 70.0));
    EXPECT_NEAR(sky.band_radiance(lwir, 90.0), lwir.radiance(290.0), 1e-9);
    // A vertical facet sees half sky, half ground at 290 K.
    EXPECT_NEAR(
        sky.facet_irradiance_w_m2(90.0, 290.0),
        0.5 * sky.horizontal_irradiance_w_m2() + 0.5 * kStefanBoltzmann * std::pow(290.0, 4), 1e-9);
}

}  // namespace
}  // namespace tirpol::thermal
