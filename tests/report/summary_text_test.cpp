// The Summary paragraph on constructed comparison results: every region consistent; one region
// flagged; verdicts without power; pixels outside the calibration range; and that it always says
// what each part of σ contains.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tirpol/report/comparison_report.h"

using namespace tirpol::report;
using ::testing::HasSubstr;
using ::testing::Not;

namespace {

// A region whose S0, S1, S2 tests have the given mean difference, σ_mean and simulated means; the
// verdict and detectable bias follow the design's defaults (critical t 2.39, detectable 3.23 σ
// at large ν: docs/report.md).
RegionResult region(const std::string& name, std::array<double, 3> difference, double sigma_mean,
                    std::array<double, 3> simulated_mean) {
    RegionResult r;
    r.name = name;
    r.pixel_count = 100;
    r.verdict = Agreement::ConsistentWithNoise;
    for (std::size_t i = 0; i < 3; ++i) {
        const Quantity q = kZQuantities[i];
        QuantityVerdict v;
        v.mean.pixel_count = 100;
        v.mean.difference = difference[i];
        v.mean.combined.sigma = sigma_mean;
        v.mean.t = difference[i] / sigma_mean;
        v.mean.critical_t = 2.39;
        v.mean.detectable_bias = 3.23 * sigma_mean;
        v.mean.verdict = std::abs(v.mean.t) > v.mean.critical_t ? Agreement::ExceedsNoise
                                                                : Agreement::ConsistentWithNoise;
        v.sigma.verdict = SigmaCheck::Plausible;
        r.verdict = worse(r.verdict, v.mean.verdict);
        r.verdicts[q] = v;
        QuantityStats s;
        s.pixel_count = 100;
        s.simulated_mean = simulated_mean[i];
        s.measured_mean = simulated_mean[i] + difference[i];
        r.stats[q] = s;
    }
    return r;
}

CompareResult result_of(std::vector<RegionResult> regions) {
    CompareResult r;
    r.width = 160;
    r.height = 120;
    r.units = "W/(m^2 sr)";
    r.regions = std::move(regions);
    r.measured_sigma_contains = "temporal noise (independent from pixel to pixel)";
    r.simulated_sigma_contains = "Monte Carlo noise of the render only";
    r.registration.residual_shift_px = {0.03, 0.04};
    r.calibration_range = CalibrationRange{0.0, 263.0, 313.0};
    return r;
}

}  // namespace

TEST(ReportSummaryText, AllRegionsConsistentSaysSoAndThatTheVerdictsHavePower) {
    const auto text = summary_paragraph(
        result_of({region("panel_a", {0.1, 0.001, -0.001}, 0.05, {30.0, -0.5, 0.2}),
                   region("panel_b", {-0.05, 0.0, 0.002}, 0.05, {28.0, -0.3, 0.4})}));
    EXPECT_THAT(text, HasSubstr("All 2 regions agree with the simulation within the noise "
                                "(panel_a and panel_b)"));
    EXPECT_THAT(text, Not(HasSubstr("differ from the simulation")));
    EXPECT_THAT(text, HasSubstr("Every measured pixel lies inside the blackbody calibration "
                                "range (263.0–313.0 K)"));
    EXPECT_THAT(text, HasSubstr("The verdicts have power"));
    // The detectable bias 3.23 × 0.05 is quoted per quantity.
    EXPECT_THAT(text, HasSubstr("S0 0.16, S1 0.16, S2 0.16 W/(m^2 sr)"));
    EXPECT_EQ(text.find('\n'), std::string::npos) << "one paragraph";
}

TEST(ReportSummaryText, OneFlaggedRegionIsNamedWithItsQuantityAndSize) {
    const auto text = summary_paragraph(
        result_of({region("panel_a", {0.1, 0.001, -0.001}, 0.05, {30.0, -0.5, 0.2}),
                   region("flat_black_paint", {0.02, 0.5, 0.0}, 0.05, {29.0, -0.6, 0.3}),
                   region("background", {0.0, 0.0, 0.0}, 0.05, {20.0, -0.2, 0.1})}));
    EXPECT_THAT(text, HasSubstr("1 of 3 regions differ from the simulation by more than the "
                                "noise: flat_black_paint in S1 by +0.5 W/(m^2 sr) (10.0 σ of "
                                "the region mean)"));
    EXPECT_THAT(text, HasSubstr("Within the noise: panel_a and background"));
    EXPECT_THAT(text, HasSubstr("material, temperature, geometry"));  // why it can differ
    EXPECT_THAT(text, Not(HasSubstr("All 3 regions agree")));
}

TEST(ReportSummaryText, VerdictsWithoutPowerAreNamed) {
    // S1 and S2 simulated means of ±0.01 under a detectable bias of 3.23 × 0.05: a simulation of
    // zero would pass as well. S0 (30) keeps its power.
    const auto some = summary_paragraph(
        result_of({region("panel_a", {0.0, 0.0, 0.0}, 0.05, {30.0, -0.01, 0.5}),
                   region("panel_b", {0.0, 0.0, 0.0}, 0.05, {30.0, -0.5, 0.01})}));
    EXPECT_THAT(some, HasSubstr("No power in panel_a S1 and panel_b S2"));
    EXPECT_THAT(some, Not(HasSubstr("The verdicts have power")));

    const auto none =
        summary_paragraph(result_of({region("panel_a", {0.0, 0.0, 0.0}, 10.0, {30.0, -0.5, 0.5})}));
    EXPECT_THAT(none, HasSubstr("None of the verdicts has power: panel_a S0, panel_a S1 and "
                                "panel_a S2"));
    EXPECT_FALSE(verdict_has_power(result_of({region("p", {0, 0, 0}, 10.0, {30, 1, 1})}).regions[0],
                                   Quantity::S0));
    EXPECT_TRUE(verdict_has_power(result_of({region("p", {0, 0, 0}, 1.0, {30, 1, 1})}).regions[0],
                                  Quantity::S0));
    EXPECT_FALSE(verdict_has_power(result_of({region("p", {0, 0, 0}, 1.0, {30, 1, 1})}).regions[0],
                                   Quantity::DoLP));  // not tested
}

TEST(ReportSummaryText, PixelsOutsideTheCalibrationRangeAreCountedAndTheirErrorNamed) {
    auto r = result_of({region("panel_a", {0.0, 0.0, 0.0}, 0.05, {30.0, -0.5, 0.5})});
    r.calibration_range = CalibrationRange{1.0, 283.0, 293.0};
    const auto all_outside = summary_paragraph(r);
    EXPECT_THAT(all_outside,
                HasSubstr("100.0 % of the measured pixels (about 19200 of 19200) lie outside the "
                          "blackbody calibration range (283.0–293.0 K)"));
    EXPECT_THAT(all_outside, HasSubstr("an error no σ here contains"));

    r.calibration_range->outside_fraction = 0.25;
    EXPECT_THAT(summary_paragraph(r), HasSubstr("25.0 % of the measured pixels (about 4800 of "
                                                "19200)"));

    r.calibration_range.reset();
    EXPECT_THAT(summary_paragraph(r),
                HasSubstr("does not state its radiometric calibration range"));
}

TEST(ReportSummaryText, SaysWhatEachPartOfSigmaContains) {
    const auto text =
        summary_paragraph(result_of({region("panel_a", {0.0, 0.0, 0.0}, 0.05, {30.0, -0.5, 0.5})}));
    EXPECT_THAT(text, HasSubstr("three parts: the measurement's (temporal noise (independent from "
                                "pixel to pixel)); the render's (Monte Carlo noise of the render "
                                "only); and the registration's (the residual misalignment of "
                                "0.05 px"));
}

// What `tirpol compare` prints: the registration with its residual (0.03, 0.04 px → 0.050), the
// paragraph, a row per region whose columns line up by displayed width (σ is two bytes), the flag
// of a region that exceeds the noise, and the report path last.
TEST(ReportSummaryText, ComparisonTextTabulatesRegionsAndEndsWithTheReport) {
    CompareResult r = result_of(
        {region("panel_a", {0.1, 0.001, -0.001}, 0.05, {30.0, -0.5, 0.2}),
         region("flat_black_paint_long_name", {0.02, 0.5, 0.0}, 0.05, {29.0, -0.6, 0.3})});
    r.html = "out/report.html";
    r.notes = {"something to know"};
    const std::string text = comparison_text(r);
    EXPECT_THAT(text, HasSubstr("residual misalignment 0.050 px\n"));
    EXPECT_THAT(text, HasSubstr(summary_paragraph(r) + "\n"));
    const auto row_of = [&](const std::string& name) {
        const auto at = text.find("\n" + name + " ");
        return text.substr(at + 1, text.find('\n', at + 1) - at - 1);
    };
    EXPECT_THAT(row_of("flat_black_paint_long_name"), HasSubstr("+10.0 (0.16) EXCEEDS"));
    EXPECT_THAT(row_of("panel_a"), HasSubstr("+2.0 (0.16) ok"));
    // The name column is as wide as the longest name: both rows put "100" at the same column.
    EXPECT_EQ(row_of("panel_a").find(" 100 "), row_of("flat_black_paint_long_name").find(" 100 "));
    EXPECT_THAT(text, HasSubstr("note: something to know\n"));
    EXPECT_EQ(text.substr(text.size() - std::string("report: out/report.html\n").size()),
              "report: out/report.html\n");
}
