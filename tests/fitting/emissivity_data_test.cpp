// Loading measured emissivity: the calibration module's CSV layout (2σ columns halved to 1σ), the
// hand-written 1σ layout, band splitting, and clear errors for bad data (NaN, angles outside 0–90°,
// zero uncertainties, missing columns, non-numbers, too few samples for the free parameters).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "error_of.h"
#include "test_support.h"
#include "tirpol/core/error.h"
#include "tirpol/fitting/microfacet_fit.h"

namespace tirpol::fitting {
namespace {

using ::testing::HasSubstr;

// The header written by calibration's emissivity_csv (calibration/emissivity_extraction.h).
const char* kCalibrationHeader =
    "name,view_angle_deg,temperature_k,pixels,l_dw_w_m2_sr,l_bb_w_m2_sr,eps_s0,eps_s0_2sigma,eps_"
    "s1,eps_s1_2sigma,"
    "eps_s2,eps_s2_2sigma\n";

std::string error_of(const std::filesystem::path& path) {
    return tirpol::test::error_of([&] { load_emissivity_csv(path); });
}

TEST(EmissivityData, ReadsCalibrationCsvAndHalvesTwoSigmaColumns) {
    tirpol::test::TempDir dir;
    tirpol::test::write_text(
        dir / "e.csv", std::string("# from tirpol extract-emissivity\n") + kCalibrationHeader +
                           "panel_0,0,300,400,5,40,0.95,0.01,-0.001,0.004,0,0.004\n"
                           "panel_60,60,300,400,5,40,0.91,0.02,-0.03,0.006,0,0.004\n");
    const auto d = load_emissivity_csv(dir / "e.csv", 9.5);
    ASSERT_EQ(d.size(), 1u);
    EXPECT_DOUBLE_EQ(d[0].wavelength_um, 9.5);
    ASSERT_EQ(d[0].samples.size(), 2u);
    EXPECT_EQ(d[0].samples[1].name, "panel_60");
    EXPECT_DOUBLE_EQ(d[0].samples[1].angle_deg, 60.0);
    EXPECT_DOUBLE_EQ(d[0].samples[1].eps_s0, 0.91);
    EXPECT_DOUBLE_EQ(d[0].samples[1].eps_s0_std, 0.01);
    EXPECT_DOUBLE_EQ(d[0].samples[1].eps_s1, -0.03);
    EXPECT_DOUBLE_EQ(d[0].samples[1].eps_s1_std, 0.003);
}

TEST(EmissivityData, SplitsBandsAndRoundTripsItsOwnCsv) {
    EmissivityDataset a{
        "a", 8.5, {{10, 0.9, 0.01, -0.01, 0.002, "x"}, {50, 0.88, 0.01, -0.04, 0.002, "y"}}};
    EmissivityDataset b{"b", 11.0, {{20, 0.93, 0.02, -0.02, 0.003, "z"}}};
    tirpol::test::TempDir dir;
    tirpol::test::write_text(dir / "e.csv", emissivity_csv({a, b}));
    const auto d = load_emissivity_csv(dir / "e.csv");
    ASSERT_EQ(d.size(), 2u);
    EXPECT_DOUBLE_EQ(d[0].wavelength_um, 8.5);
    EXPECT_DOUBLE_EQ(d[1].wavelength_um, 11.0);
    ASSERT_EQ(d[0].samples.size(), 2u);
    EXPECT_DOUBLE_EQ(d[0].samples[1].eps_s1, -0.04);
    EXPECT_DOUBLE_EQ(d[0].samples[1].eps_s1_std, 0.002);
    EXPECT_DOUBLE_EQ(d[1].samples[0].eps_s0_std, 0.02);
}

TEST(EmissivityData, AcceptsHandWrittenOneSigmaColumns) {
    tirpol::test::TempDir dir;
    tirpol::test::write_text(
        dir / "e.csv", "angle_deg,e_s0,e_s0_sigma,e_s1,e_s1_sigma\n30,0.94,0.005,-0.01,0.002\n");
    const auto d = load_emissivity_csv(dir / "e.csv");
    EXPECT_DOUBLE_EQ(d.at(0).samples.at(0).eps_s0_std, 0.005);
}

TEST(EmissivityData, BadDataGiveClearErrors) {
    tirpol::test::TempDir dir;
    const std::string ok_row = "p,30,300,1,1,2,0.94,0.01,-0.01,0.004,0,0.004\n";
    struct Bad {
        const char* row;
        const char* expected;
    } cases[] = {
        {"p,30,300,1,1,2,nan,0.01,-0.01,0.004,0,0.004\n", "eps_s0 is nan"},
        {"p,95,300,1,1,2,0.9,0.01,-0.01,0.004,0,0.004\n", "outside [0°, 90°]"},
        {"p,-5,300,1,1,2,0.9,0.01,-0.01,0.004,0,0.004\n", "outside [0°, 90°]"},
        {"p,30,300,1,1,2,0.9,0,-0.01,0.004,0,0.004\n", "uncertainties must be > 0"},
        {"p,30,300,1,1,2,0.9,0.01,-0.01,-0.004,0,0.004\n", "uncertainties must be > 0"},
        {"p,30,300,1,1,2,0.9x,0.01,-0.01,0.004,0,0.004\n",
         "column eps_s0: \"0.9x\" is not a number"},
        {"p,30,300\n", "3 cells, expected 12"},
    };
    for (const Bad& c : cases) {
        const auto path = dir / "bad.csv";
        tirpol::test::write_text(path, std::string(kCalibrationHeader) + ok_row + c.row);
        const std::string message = error_of(path);
        EXPECT_THAT(message, HasSubstr(c.expected)) << c.row;
        EXPECT_THAT(message, HasSubstr("bad.csv:3")) << "the message names file and line";
    }
    tirpol::test::write_text(dir / "nocol.csv", "view_angle_deg,eps_s0,eps_s1\n30,0.9,-0.01\n");
    EXPECT_THAT(error_of(dir / "nocol.csv"),
                HasSubstr("no column eps_s0_std (or eps_s0_2sigma, e_s0_sigma)"));
    tirpol::test::write_text(dir / "empty.csv", kCalibrationHeader);
    EXPECT_THAT(error_of(dir / "empty.csv"), HasSubstr("no data rows"));
}

TEST(EmissivityData, TooFewSamplesForTheFreeParametersIsAnError) {
    // Two angles give four residuals; the default fit has four free parameters (n, k, σ, ρ_D).
    EmissivityDataset d{"two angles",
                        10.0,
                        {{10, 0.95, 0.01, -0.01, 0.002, ""}, {60, 0.9, 0.01, -0.05, 0.002, ""}}};
    try {
        MicrofacetFitProblem problem({d}, MicrofacetFitOptions{});
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("4 residuals"));
        EXPECT_THAT(e.what(), HasSubstr("4 free parameters"));
    }
    // Fixing k makes the same data just sufficient (4 residuals > 3 parameters).
    MicrofacetFitOptions fixed;
    fixed.parameters[static_cast<std::size_t>(MicrofacetParameter::k)].fixed = true;
    EXPECT_NO_THROW(MicrofacetFitProblem({d}, fixed));
}

TEST(EmissivityData, BadSettingsAreErrors) {
    EmissivityDataset d{"d",
                        10.0,
                        {{10, 0.95, 0.01, -0.01, 0.002, ""},
                         {40, 0.94, 0.01, -0.02, 0.002, ""},
                         {60, 0.9, 0.01, -0.05, 0.002, ""}}};
    MicrofacetFitOptions o;
    o.parameters[0].initial = 7.0;  // n outside [1.05, 4]
    EXPECT_THROW(MicrofacetFitProblem({d}, o), Error);
    MicrofacetFitOptions all_fixed;
    for (auto& p : all_fixed.parameters) p.fixed = true;
    EXPECT_THROW(MicrofacetFitProblem({d}, all_fixed), Error);
    EXPECT_THROW(parameter_from_name("sigma_deg"), Error);
    EXPECT_EQ(parameter_from_name("rho_v"), MicrofacetParameter::rho_v);
}

}  // namespace
}  // namespace tirpol::fitting
