// The emissivity CSV (core/emissivity_csv.h): one writer and one reader, so a written file reads
// back exactly; the frame and the 1σ convention are explicit; the older layouts read with the
// meaning their writers gave them (missing frame column, 2σ columns, hand-written 1σ columns).

#include "tirpol/core/emissivity_csv.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tirpol/core/error.h"

namespace tirpol {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

std::string error_of(const std::string& text) {
    try {
        parse_emissivity_csv(text, "e.csv");
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

TEST(EmissivityCsv, WrittenRowsReadBackExactly) {
    EmissivityCsvRow measured{
        "panel_40", 40.0,        295.15, 480,    1.0 / 3.0, 41.25,  EmissivityFrame::Image,
        0.93,       0.004 / 3.0, -0.035, 0.0011, 0.002,     0.0012, std::nullopt,
        0};
    EmissivityCsvRow modelled;
    modelled.name = "view2";
    modelled.view_angle_deg = 75.5;
    modelled.frame = EmissivityFrame::PlaneOfEmission;
    modelled.eps_s0 = 0.1 + 0.2;
    modelled.eps_s0_std = 1e-3;
    modelled.eps_s1 = -0.2 / 3.0;
    modelled.eps_s1_std = 2e-3;
    modelled.wavelength_um = 11.0;
    const std::string text = emissivity_csv_text({measured, modelled});
    EXPECT_THAT(text,
                testing::StartsWith(
                    "name,view_angle_deg,temperature_k,pixels,l_dw_w_m2_sr,l_bb_w_m2_sr,frame,"
                    "eps_s0,eps_s0_std,eps_s1,eps_s1_std,eps_s2,eps_s2_std,wavelength_um\n"));
    const auto rows = parse_emissivity_csv(text, "e.csv");
    ASSERT_EQ(rows.size(), 2u);
    const EmissivityCsvRow& a = rows[0];
    EXPECT_EQ(a.name, "panel_40");
    EXPECT_EQ(a.line, 2);
    EXPECT_EQ(a.frame, EmissivityFrame::Image);
    EXPECT_EQ(a.temperature_k, 295.15);
    EXPECT_EQ(a.pixels, 480u);
    EXPECT_EQ(a.l_dw_w_m2_sr, 1.0 / 3.0);
    EXPECT_EQ(a.eps_s0_std, 0.004 / 3.0);
    EXPECT_EQ(a.eps_s2, 0.002);
    EXPECT_EQ(a.eps_s2_std, 0.0012);
    EXPECT_FALSE(a.wavelength_um);
    const EmissivityCsvRow& b = rows[1];
    EXPECT_EQ(b.frame, EmissivityFrame::PlaneOfEmission);
    EXPECT_EQ(b.eps_s0, 0.1 + 0.2);
    EXPECT_EQ(b.eps_s1, -0.2 / 3.0);
    EXPECT_FALSE(b.temperature_k);
    EXPECT_FALSE(b.pixels);
    EXPECT_FALSE(b.eps_s2);
    EXPECT_EQ(b.wavelength_um, 11.0);
}

// Before the frame column, `tirpol extract-emissivity` wrote image-frame values with 2σ columns;
// the hand-written layout (docs/fitting.md) and fitting's writer (with wavelength_um) meant the
// plane of emission.
TEST(EmissivityCsv, OlderLayoutsReadWithTheirWritersMeaning) {
    const auto calibration = parse_emissivity_csv(
        "name,view_angle_deg,temperature_k,pixels,l_dw_w_m2_sr,l_bb_w_m2_sr,eps_s0,eps_s0_2sigma,"
        "eps_s1,"
        "eps_s1_2sigma,eps_s2,eps_s2_2sigma\npanel,40,295,480,5,40,0.93,0.01,-0.035,0.004,0.002,0."
        "006\n",
        "old.csv");
    EXPECT_EQ(calibration.at(0).frame, EmissivityFrame::Image);
    EXPECT_DOUBLE_EQ(calibration[0].eps_s0_std, 0.005);
    EXPECT_DOUBLE_EQ(calibration[0].eps_s1_std, 0.002);
    EXPECT_DOUBLE_EQ(*calibration[0].eps_s2_std, 0.003);

    const auto twin = parse_emissivity_csv(
        "name,view_angle_deg,temperature_k,pixels,l_dw_w_m2_sr,l_bb_w_m2_sr,eps_s0,eps_s0_2sigma,"
        "eps_s1,"
        "eps_s1_2sigma,eps_s2,eps_s2_2sigma,wavelength_um\nv0,30,,,,,0.93,0.01,-0.02,0.004,,,10\n",
        "old_twin.csv");
    EXPECT_EQ(twin.at(0).frame, EmissivityFrame::PlaneOfEmission);
    EXPECT_FALSE(twin[0].eps_s2);

    const auto hand = parse_emissivity_csv(
        "angle_deg,e_s0,e_s0_sigma,e_s1,e_s1_sigma\n30,0.94,0.005,-0.01,0.002\n", "hand.csv");
    EXPECT_EQ(hand.at(0).frame, EmissivityFrame::PlaneOfEmission);
    EXPECT_DOUBLE_EQ(hand[0].eps_s0_std, 0.005);  // 1σ as written
    EXPECT_DOUBLE_EQ(hand[0].view_angle_deg, 30.0);
}

TEST(EmissivityCsv, BadFilesGiveErrorsNamingFileLineAndColumn) {
    const std::string header = "name,view_angle_deg,frame,eps_s0,eps_s0_std,eps_s1,eps_s1_std\n";
    EXPECT_THAT(error_of(header + "p,30,camera,0.9,0.01,-0.01,0.002\n"),
                AllOf(HasSubstr("e.csv:2"), HasSubstr("column frame: \"camera\""),
                      HasSubstr("plane_of_emission")));
    EXPECT_THAT(error_of(header + "p,30,image,0.9x,0.01,-0.01,0.002\n"),
                AllOf(HasSubstr("e.csv:2"), HasSubstr("column eps_s0: \"0.9x\" is not a number")));
    EXPECT_THAT(error_of(header + "p,30,image\n"), HasSubstr("3 cells, expected 7"));
    EXPECT_THAT(error_of("view_angle_deg,eps_s0,eps_s1\n30,0.9,-0.01\n"),
                AllOf(HasSubstr("e.csv:1"), HasSubstr("no column eps_s0_std")));
    EXPECT_THAT(error_of("# only a comment\n"), HasSubstr("empty file"));
    EXPECT_THAT(error_of(header), HasSubstr("no data rows"));
    EmissivityCsvRow comma;
    comma.name = "panel, left";
    EXPECT_THAT([&] { emissivity_csv_text({comma}); },
                testing::ThrowsMessage<Error>(HasSubstr("\"panel, left\"")));
}

}  // namespace
}  // namespace tirpol
