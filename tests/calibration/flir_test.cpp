// The FLIR radiometric model: the published equation with published camera constants, the
// published atmospheric constants, physical invariants and round trips.

#include <gtest/gtest.h>

#include "tirpol/calibration/flir_image.h"
#include "tirpol/core/error.h"

namespace tirpol::calibration {
namespace {

// FLIR SC660 constants as listed in G. Tattersall's Thermimage (R package, raw2temp.R):
// PlanckR1 = 21106.77, PlanckB = 1501, PlanckF = 1, PlanckO = −7340, PlanckR2 = 0.012545258.
const FlirPlanck kSc660{21106.77, 0.012545258, 1501.0, 1.0, -7340.0};

TEST(Flir, BlackbodyEquationWithSc660Constants) {
    // Thermimage's example raw2temp(18109, E=1, OD=0, 20 °C, ...): T = B/ln(R1/(R2·(raw+O)) + F)
    // = 1501/ln(21106.77/(0.012545258·10769) + 1) = 296.7743 K (23.62 °C), evaluated by hand.
    EXPECT_NEAR(flir_blackbody_temperature(kSc660, 18109.0), 296.7743, 1e-3);
    FlirConditions blackbody;  // E = 1, d = 0, no window: the measurement is the blackbody raw
    EXPECT_NEAR(flir_temperature_from_raw(kSc660, 18109.0, blackbody), 296.7743, 1e-3);
    for (double t = 250.0; t <= 400.0; t += 10.0)
        EXPECT_NEAR(flir_blackbody_temperature(kSc660, flir_blackbody_raw(kSc660, t)), t, 1e-9);
}

TEST(Flir, AtmosphericTransmissionWithPublishedConstants) {
    // X = 1.9, α1 = 0.006569, α2 = 0.01262, β1 = −0.002276, β2 = −0.00667 (Minkina & Dudzik 2009;
    // FLIR's AtmosphericTrans* EXIF tags). At 20 °C, 50 % RH: H2O = 8.56398 (mmHg); over 10 m
    // τ = 1.9·e^(−√10·(0.006569 − 0.002276·√8.564)) − 0.9·e^(−√10·(0.01262 − 0.00667·√8.564)) =
    // 0.980699.
    EXPECT_NEAR(flir_atmospheric_transmission(10.0, 293.15, 50.0), 0.980699, 1e-6);
    EXPECT_NEAR(flir_atmospheric_transmission(100.0, 293.15, 50.0), 0.937455, 1e-6);
    EXPECT_DOUBLE_EQ(flir_atmospheric_transmission(0.0, 293.15, 50.0), 1.0);
    // More water vapour absorbs more.
    EXPECT_LT(flir_atmospheric_transmission(50.0, 303.15, 90.0),
              flir_atmospheric_transmission(50.0, 303.15, 20.0));
}

TEST(Flir, IsothermalSceneReadsItsTemperatureWhateverEmissivityDistanceAndWindow) {
    // Kirchhoff: object, surroundings, air and window all at T — every path term is a blackbody at
    // T.
    FlirConditions c;
    c.emissivity = 0.6;
    c.distance_m = 80.0;
    c.humidity_pct = 70.0;
    c.window_transmission = 0.8;
    c.reflected_k = c.atmosphere_k = c.window_k = 305.0;
    EXPECT_NEAR(flir_raw_from_temperature(kSc660, 305.0, c), flir_blackbody_raw(kSc660, 305.0),
                1e-6);
}

TEST(Flir, CorrectionsRoundTripAndGoTheRightWay) {
    FlirConditions c;
    c.emissivity = 0.95;
    c.distance_m = 20.0;
    c.reflected_k = 250.0;  // cold sky reflected
    c.window_transmission = 0.96;
    c.window_k = 288.0;
    for (double t = 260.0; t <= 380.0; t += 15.0)
        EXPECT_NEAR(flir_temperature_from_raw(kSc660, flir_raw_from_temperature(kSc660, t, c), c),
                    t, 1e-6);
    // A non-black object reflecting a cold sky looks colder than it is without the correction.
    const double raw = flir_raw_from_temperature(kSc660, 320.0, c);
    EXPECT_LT(flir_blackbody_temperature(kSc660, raw), 320.0);
}

TEST(Flir, BadConstantsAndConditionsAreRejected) {
    FlirConditions c;
    c.emissivity = 0.0;
    EXPECT_THROW(validate_flir(kSc660, c), Error);
    c.emissivity = 0.9;
    c.humidity_pct = 140.0;
    EXPECT_THROW(validate_flir(kSc660, c), Error);
    EXPECT_THROW(validate_flir(FlirPlanck{}, FlirConditions{}), Error);
    EXPECT_NO_THROW(validate_flir(kSc660, FlirConditions{}));
}

}  // namespace
}  // namespace tirpol::calibration
