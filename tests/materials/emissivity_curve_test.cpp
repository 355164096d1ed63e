// Emissivity curves as the CLI writes them: angle specifications, CSV columns, band averaging.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "smooth_fresnel.h"
#include "tirpol/core/error.h"
#include "tirpol/materials/emissivity.h"
#include "tirpol/materials/microfacet.h"

namespace tirpol::materials {
namespace {

TEST(EmissivityCurve, ParsesListsAndRanges) {
    EXPECT_EQ(parse_angles_deg("0,45,60"), (std::vector<double>{0, 45, 60}));
    const auto r = parse_angles_deg("0:85:5");
    ASSERT_EQ(r.size(), 18u);
    EXPECT_DOUBLE_EQ(r.back(), 85.0);
    EXPECT_EQ(parse_angles_deg("10:10:1"), (std::vector<double>{10}));
    for (const char* bad : {"0:95:5", "a,b", "10:0:5", "0:10:0", "0:10", "", "-1"})
        EXPECT_THROW(parse_angles_deg(bad), Error) << bad;
    try {
        parse_angles_deg("0,x");
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), ::testing::HasSubstr("\"x\" is not a number"));
    }
}

TEST(EmissivityCurve, CsvHasTheDocumentedColumns) {
    const SmoothFresnelBrdf water(RefractiveIndexTable::constant({1.218, 0.0508}));
    const auto rows = emissivity_curve(water, {0.0, 60.0}, 10.0);
    const std::string csv = emissivity_csv(rows);
    EXPECT_EQ(csv.substr(0, csv.find('\n')), "angle_deg,e_s0,e_s1,e_s2,e_s3,dolp,dhr");
    EXPECT_NEAR(rows[1].dhr, 1.0 - rows[1].e(0), 1e-15);
    EXPECT_NEAR(rows[1].dolp, std::abs(rows[1].e(1)) / rows[1].e(0), 1e-12);
}

// For a material whose parameters do not depend on wavelength, the Planck-weighted band average
// equals the single-wavelength emissivity (the weights sum to one); for a tabulated material it
// lies between the extremes over the band.
TEST(EmissivityCurve, BandAverageIsAWeightedMean) {
    MicrofacetParameters p;
    p.index = RefractiveIndexTable::constant({1.6, 0.1});
    p.sigma = 0.3;
    const MicrofacetBrdf paint(p);
    const auto band = emissivity_curve(paint, {0.0, 70.0}, Band(8.0, 14.0), 300.0);
    const auto mono = emissivity_curve(paint, {0.0, 70.0}, 11.0);
    for (std::size_t i = 0; i < 2; ++i)
        EXPECT_LT((band[i].e - mono[i].e).cwiseAbs().maxCoeff(), 2e-4);

    const SmoothFresnelBrdf water(
        RefractiveIndexTable({8.0, 12.0}, {1.29, 1.11}, {0.034, 0.199}, "test"));
    const double avg = emissivity_curve(water, {0.0}, Band(8.0, 12.0), 300.0)[0].e(0);
    const double e8 = emissivity_curve(water, {0.0}, 8.0)[0].e(0),
                 e12 = emissivity_curve(water, {0.0}, 12.0)[0].e(0);
    EXPECT_GT(avg, std::min(e8, e12));
    EXPECT_LT(avg, std::max(e8, e12));
    EXPECT_THROW(emissivity_curve(water, {0.0}, Band(8.0, 14.0), 300.0),
                 Error);  // outside the data
}

}  // namespace
}  // namespace tirpol::materials
