// Planck's law, band integration and brightness temperature against published constants.

#include "tirpol/core/radiometry.h"

#include <gtest/gtest.h>

#include <cmath>

#include "test_support.h"
#include "tirpol/core/error.h"
#include "tirpol/core/geometry.h"

namespace tirpol {
namespace {

// CODATA 2018 (Tiesinga et al., Rev. Mod. Phys. 93, 025010, 2021): Stefan–Boltzmann constant
// σ = 5.670374419e-8 W m⁻² K⁻⁴ and Wien wavelength displacement constant b = 2.897771955e-3 m·K.
constexpr double kSigmaCodata2018 = 5.670374419e-8;
constexpr double kWienB_um_K = 2897.771955;

TEST(Planck, RadiationConstantsMatchCodata2018) {
    // c1L = 2hc² = 1.191042972e-16 W·m²/sr and c2 = hc/k = 1.438776877e-2 m·K (CODATA 2018).
    EXPECT_NEAR(kC1L_W_um4_per_m2_sr, 1.191042972e8, 1e-1);
    EXPECT_NEAR(kC2_um_K, 14387.76877, 1e-5);
}

TEST(Planck, StefanBoltzmannConstantFollowsFromTheExactConstants) {
    // σ = 2π⁵k⁴/(15h³c²) with the exact SI h, c, k gives CODATA 2018's σ to its 10 digits.
    const double sigma = 2.0 * std::pow(kPi, 5) * std::pow(kBoltzmannK, 4) /
                         (15.0 * std::pow(kPlanckH, 3) * kSpeedOfLight * kSpeedOfLight);
    EXPECT_NEAR(kStefanBoltzmann / sigma, 1.0, 1e-9);
    EXPECT_EQ(kStefanBoltzmann, kSigmaCodata2018);
}

TEST(Planck, TotalRadianceIsStefanBoltzmannOverPi) {
    // ∫ L(λ,T) dλ = σT⁴/π for a Lambertian blackbody. The band 0.2–1000 µm (the longest wavelength
    // a Band accepts) misses the tail beyond Λ = 1000 µm, about 6e-6 of the total, added
    // analytically from the series of Planck's law in x = hc/(λkT) < 0.06 there: L = (2ckT/λ⁴)(1 −
    // x/2 + x²/12 − …), so ∫_Λ^∞ L dλ = 2ckT/(3Λ³) − hc²/(4Λ⁴) + h²c³/(30kTΛ⁵) (next term below
    // 1e-12 of the total).
    const Band all(0.2, 1000.0, std::nullopt, 1.0);
    for (double t : {250.0, 300.0, 400.0}) {
        const double expected = kSigmaCodata2018 * std::pow(t, 4) / kPi;
        const double lambda_m = 1000e-6;
        const double c = kSpeedOfLight, h = kPlanckH, k = kBoltzmannK;
        const double tail = 2.0 * c * k * t / (3.0 * std::pow(lambda_m, 3)) -
                            h * c * c / (4.0 * std::pow(lambda_m, 4)) +
                            h * h * c * c * c / (30.0 * k * t * std::pow(lambda_m, 5));
        EXPECT_NEAR((all.radiance(t) + tail) / expected, 1.0, 2e-8) << "T = " << t;
    }
}

TEST(Planck, PeakFollowsWiensDisplacementLaw) {
    for (double t : {250.0, 300.0, 1000.0}) {
        // Golden-section search for the maximum of L(λ).
        double a = 0.5 * kWienB_um_K / t, b = 2.0 * kWienB_um_K / t;
        const double g = (std::sqrt(5.0) - 1.0) / 2.0;
        for (int i = 0; i < 200; ++i) {
            const double c = b - g * (b - a), d = a + g * (b - a);
            if (planck_radiance(c, t) > planck_radiance(d, t))
                b = d;
            else
                a = c;
        }
        EXPECT_NEAR(0.5 * (a + b) * t, kWienB_um_K, 1e-3) << "T = " << t;
    }
}

TEST(Planck, DerivativeMatchesFiniteDifference) {
    for (double wl : {3.0, 8.0, 10.0, 14.0})
        for (double t : {200.0, 300.0, 350.0}) {
            const double h = 1e-3;
            const double fd = (planck_radiance(wl, t + h) - planck_radiance(wl, t - h)) / (2 * h);
            EXPECT_NEAR(planck_radiance_dT(wl, t) / fd, 1.0, 1e-7);
        }
}

TEST(Planck, NonPositiveTemperatureGivesZero) {
    EXPECT_EQ(planck_radiance(10.0, 0.0), 0.0);
    EXPECT_EQ(planck_radiance(10.0, -5.0), 0.0);
    EXPECT_EQ(planck_radiance_dT(10.0, 0.0), 0.0);
}

TEST(Band, BrightnessTemperatureRoundTripsToBetterThanOneMillikelvin) {
    const Band lwir(8.0, 14.0), mwir(3.0, 5.0);
    for (const Band* band : {&lwir, &mwir})
        for (double t = 180.0; t <= 500.0; t += 7.3)
            EXPECT_NEAR(band->brightness_temperature(band->radiance(t)), t, 1e-3) << "T = " << t;
}

TEST(Band, BrightnessTemperatureOfInvalidRadianceIsNaN) {
    const Band lwir(8.0, 14.0);
    EXPECT_TRUE(std::isnan(lwir.brightness_temperature(0.0)));
    EXPECT_TRUE(std::isnan(lwir.brightness_temperature(-1.0)));
    EXPECT_TRUE(std::isnan(lwir.brightness_temperature(std::nan(""))));
}

TEST(Band, DerivativeMatchesFiniteDifference) {
    const Band lwir(8.0, 14.0);
    const double fd = (lwir.radiance(300.001) - lwir.radiance(299.999)) / 0.002;
    EXPECT_NEAR(lwir.radiance_dT(300.0) / fd, 1.0, 1e-6);
}

TEST(Band, PiecewiseLinearResponseIsIntegratedExactly) {
    // A triangle 8–10–12 µm with peak 1 has area ½·4·1 = 2 µm; quadrature panels break at the
    // knots.
    const SpectralResponse tri({8.0, 10.0, 12.0}, {0.0, 1.0, 0.0});
    const Band band(7.0, 13.0, tri);
    EXPECT_NEAR(band.effective_width_um(), 2.0, 1e-12);
    // Brightness temperature with an RSR still round-trips.
    EXPECT_NEAR(band.brightness_temperature(band.radiance(287.0)), 287.0, 1e-3);
}

TEST(Band, UnitResponseEqualsPlainBand) {
    const SpectralResponse flat({7.0, 15.0}, {1.0, 1.0});
    const Band with(8.0, 14.0, flat), without(8.0, 14.0);
    EXPECT_NEAR(with.radiance(300.0) / without.radiance(300.0), 1.0, 1e-12);
}

TEST(Band, InvalidLimitsAreRejected) {
    EXPECT_THROW(Band(14.0, 8.0), Error);
    EXPECT_THROW(Band(0.0, 8.0), Error);
    const SpectralResponse outside({1.0, 2.0}, {1.0, 1.0});
    EXPECT_THROW(Band(8.0, 14.0, outside), Error);
}

TEST(SpectralResponse, LoadsCsvWithHeaderAndComments) {
    test::TempDir dir;
    test::write_text(
        dir / "rsr.csv",
        "# FLIR Tau 2 (illustrative)\nresponse,wavelength_um\n0.0,7.5\n1.0,10\n0.0,13.5\n");
    const auto rsr = SpectralResponse::load_csv(dir / "rsr.csv");
    EXPECT_DOUBLE_EQ(rsr(10.0), 1.0);
    EXPECT_DOUBLE_EQ(rsr(8.75), 0.5);
    EXPECT_DOUBLE_EQ(rsr(14.0), 0.0);
}

void expect_error_containing(const std::function<void()>& f, const std::string& needle) {
    try {
        f();
        ADD_FAILURE() << "expected tirpol::Error containing '" << needle << "'";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
}

TEST(SpectralResponse, BadFilesGiveClearErrors) {
    test::TempDir dir;
    test::write_text(dir / "nohdr.csv", "lambda,r\n8,1\n");
    expect_error_containing([&] { SpectralResponse::load_csv(dir / "nohdr.csv"); },
                            "'wavelength_um' and 'response'");
    test::write_text(dir / "text.csv", "wavelength_um,response\n8,abc\n9,1\n");
    expect_error_containing([&] { SpectralResponse::load_csv(dir / "text.csv"); },
                            "text.csv:2: column 'response'");
    test::write_text(dir / "order.csv", "wavelength_um,response\n9,1\n8,1\n");
    expect_error_containing([&] { SpectralResponse::load_csv(dir / "order.csv"); }, "increase");
    expect_error_containing([&] { SpectralResponse::load_csv(dir / "missing.csv"); },
                            "cannot open");
}

}  // namespace
}  // namespace tirpol
