// Emissivity extraction (paper eq 17): a synthetic Stokes image built from known polarized
// emissivities, downwelled radiance and target temperatures gives them back within twice the
// reported standard uncertainty (1σ, `*_std`), whose size matches the scatter of the estimates over
// noise draws.

#include "tirpol/calibration/emissivity_extraction.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "stokes_image.h"
#include "test_support.h"
#include "tirpol/core/emissivity_csv.h"
#include "tirpol/core/error.h"

namespace tirpol::calibration {
namespace {

constexpr int kW = 80, kH = 40;

Image scene(const Band& band, double noise, unsigned seed) {
    // Left: an aluminium reflector (S0 = L_dw of a 240 K sky); middle: a panel at 295 K with
    // ε_S0 = 0.92, ε_S1 = −0.03 (vertical emission); right: an in-scene blackbody at 295 K.
    std::mt19937 rng(seed);
    std::normal_distribution<double> n(0.0, noise);
    const double l_dw = band.radiance(240.0), l_bb = band.radiance(295.0);
    return test::stokes_image(kW, kH, [&](int x, int) -> std::array<double, 3> {
        double a = l_dw, b = 0.0, c = 0.0;
        if (x >= 30 && x < 50) {
            a = 0.08 * l_dw + 0.92 * l_bb;
            b = -0.03 * (l_bb - l_dw);
            c = 0.004 * (l_bb - l_dw);
        } else if (x >= 60) {
            a = l_bb;
        }
        return {a + n(rng), b + n(rng), c + n(rng)};  // drawn in this order, left to right
    });
}

EmissivityRois rois() {
    EmissivityRois r;
    r.reflector.rect = {2, 2, 20, 36};
    EmissivityTarget contact{"panel_contact", {32, 5, 16, 30}, 40.0, 295.0, 0.1, std::nullopt};
    EmissivityTarget bb{"panel_bb", {32, 5, 16, 30},         40.0, std::nullopt,
                        0.5,        PixelRect{62, 5, 16, 30}};
    r.targets = {contact, bb};
    return r;
}

TEST(EmissivityExtraction, RecoversKnownPolarizedEmissivityWithinTwoSigma) {
    const Band band(8.0, 14.0);
    const auto results = extract_emissivity(scene(band, 0.3, 1), rois(), band);
    ASSERT_EQ(results.size(), 2u);
    for (const auto& r : results) {
        EXPECT_NEAR(r.eps_s0, 0.92, std::max(2.0 * r.eps_s0_std, 1e-9)) << r.name;
        EXPECT_NEAR(r.eps_s1, -0.03, 2.0 * r.eps_s1_std) << r.name;
        EXPECT_NEAR(r.eps_s2, 0.004, 2.0 * r.eps_s2_std) << r.name;
        EXPECT_EQ(r.pixels, 16u * 30u);
        // σ is tight enough to matter: a few thousandths of emissivity here.
        EXPECT_LT(r.eps_s1_std, 0.005);
    }
    EXPECT_NEAR(results[1].temperature_k, 295.0,
                0.1);  // brightness temperature of the blackbody region
    // Noiseless: exact.
    const auto exact = extract_emissivity(scene(band, 0.0, 1), rois(), band);
    EXPECT_NEAR(exact[0].eps_s0, 0.92, 1e-5);
    EXPECT_NEAR(exact[0].eps_s1, -0.03, 1e-5);
    const std::string csv = emissivity_csv(exact);
    EXPECT_THAT(csv, testing::StartsWith("name,view_angle_deg,temperature_k,pixels,l_dw_w_m2_sr"));
    EXPECT_THAT(csv, testing::HasSubstr("panel_contact,40,295,480,"));
    // The file states its frame (image: what was measured) and carries the result's 1σ as it is.
    const auto rows = parse_emissivity_csv(csv, "emissivity.csv");
    ASSERT_EQ(rows.size(), exact.size());
    EXPECT_EQ(rows[0].frame, EmissivityFrame::Image);
    EXPECT_EQ(rows[0].eps_s1, exact[0].eps_s1);
    EXPECT_EQ(rows[0].eps_s0_std, exact[0].eps_s0_std);
    EXPECT_EQ(rows[0].eps_s2_std, exact[0].eps_s2_std);
}

TEST(EmissivityExtraction, StdIsTheStandardDeviationOfTheEstimateOverNoiseDraws) {
    // The in-scene blackbody target: every input is a noisy ROI mean (no contact-temperature σ,
    // which this synthetic scene does not realise), so the pulls (ε − truth)/ε_std over independent
    // noise draws have unit standard deviation when ε_std is 1σ (2σ would give 0.5). 300 draws: the
    // sample standard deviation of the pulls has a relative σ of 1/√600 ≈ 4 %; ±15 % is ≈ 3.7 of
    // those.
    const Band band(8.0, 14.0);
    constexpr int kDraws = 300;
    double sum_sq[3] = {0.0, 0.0, 0.0};
    for (unsigned seed = 1; seed <= kDraws; ++seed) {
        const EmissivityResult r = extract_emissivity(scene(band, 0.3, seed), rois(), band)[1];
        sum_sq[0] += std::pow((r.eps_s0 - 0.92) / r.eps_s0_std, 2);
        sum_sq[1] += std::pow((r.eps_s1 + 0.03) / r.eps_s1_std, 2);
        sum_sq[2] += std::pow((r.eps_s2 - 0.004) / r.eps_s2_std, 2);
    }
    for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(std::sqrt(sum_sq[k] / kDraws), 1.0, 0.15) << "eps_s" << k;
}

TEST(EmissivityExtraction, RoiFileIsValidatedWithClearErrors) {
    test::TempDir dir;
    const auto good = dir / "rois.yaml";
    test::write_text(
        good,
        "reflector: {rect: [2, 2, 20, 36]}\ntargets:\n"
        "  - {name: p, rect: [32, 5, 16, 30], view_angle_deg: 40, temperature_k: 295}\n");
    const auto r = EmissivityRois::load(good.string());
    EXPECT_EQ(r.targets.at(0).rect.width, 16);
    const auto both = dir / "both.yaml";
    test::write_text(both,
                     "reflector: {rect: [2, 2, 20, 36]}\ntargets:\n"
                     "  - {name: p, rect: [32, 5, 16, 30], view_angle_deg: 40}\n");
    try {
        EmissivityRois::load(both.string());
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), testing::HasSubstr("exactly one of temperature_k"));
    }
    const auto typo = dir / "typo.yaml";
    test::write_text(typo, "reflectr: {rect: [2, 2, 20, 36]}\ntargets: []\n");
    EXPECT_THROW(EmissivityRois::load(typo.string()), Error);
    // A rectangle outside the image is named.
    EmissivityRois outside = rois();
    outside.targets[0].rect = {70, 5, 20, 10};
    try {
        extract_emissivity(scene(Band(8.0, 14.0), 0.0, 1), outside, Band(8.0, 14.0));
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), testing::HasSubstr("panel_contact"));
    }
}

}  // namespace
}  // namespace tirpol::calibration
