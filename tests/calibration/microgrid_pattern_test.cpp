// The microgrid (division-of-focal-plane) 2×2 analyzer pattern: the Sony IMX250MZR layout, parsing,
// the Stokes-completeness check and the record in an image header.

#include <gtest/gtest.h>

#include "tirpol/calibration/microgrid_stokes.h"
#include "tirpol/core/error.h"

namespace tirpol::calibration {
namespace {

TEST(MicrogridPattern, SonyLayoutPutsEachAngleAtItsDatasheetPosition) {
    // Sony IMX250MZR datasheet / FLIR & LUCID application notes: top-left 90°, top-right 45°,
    // bottom-left 135°, bottom-right 0°.
    const MicrogridPattern sony = MicrogridPattern::sony_imx250mzr();
    EXPECT_EQ(sony.angle_deg(0, 0), 90.0);
    EXPECT_EQ(sony.angle_deg(0, 1), 45.0);
    EXPECT_EQ(sony.angle_deg(1, 0), 135.0);
    EXPECT_EQ(sony.angle_deg(1, 1), 0.0);
    // The pattern repeats every 2 pixels in x and y.
    EXPECT_EQ(sony.angle_at_pixel_deg(7, 8), 45.0);
    EXPECT_EQ(sony.angle_at_pixel_deg(4, 5), 135.0);
    EXPECT_EQ(sony.cell_of(0.0), 3);
    EXPECT_EQ(MicrogridPattern::parse("sony").text(), "90,45,135,0");
}

TEST(MicrogridPattern, ParsesFourAnglesInCellOrder) {
    const MicrogridPattern p = MicrogridPattern::parse(" 0, 45,90 ,135");
    EXPECT_EQ(p.angle_deg(0, 0), 0.0);
    EXPECT_EQ(p.angle_deg(1, 1), 135.0);
    EXPECT_EQ(p.text(), "0,45,90,135");
}

TEST(MicrogridPattern, RefusesWhatCannotMeasureLinearStokes) {
    auto message = [](const char* text) {
        try {
            MicrogridPattern::parse(text, "--pattern");
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message("0,45,90,45").find("appears at cells (0,1) and (1,1)"), std::string::npos)
        << message("0,45,90,45");
    EXPECT_NE(message("0,45,90").find("has 3 angle(s)"), std::string::npos);
    EXPECT_NE(message("0,45,90,135,0").find("not a microgrid pattern"), std::string::npos);
    EXPECT_NE(message("0,45,90,180").find("[0°, 180°)"), std::string::npos);
    EXPECT_NE(message("0,45,x,135").find("--pattern"), std::string::npos);
    // Four distinct angles within 3° of each other: S1, S2 barely determined (cond(W) ≫ 10).
    EXPECT_NE(message("0,1,2,3").find("do not determine S1 and S2"), std::string::npos)
        << message("0,1,2,3");
    // Unequal but well spread angles are fine (cond(W) < 10).
    EXPECT_NO_THROW(MicrogridPattern::parse("0,60,120,30"));
}

TEST(MicrogridPattern, RoundTripsThroughImageAttributes) {
    Attributes attributes;
    MicrogridPattern::sony_imx250mzr().write_to(attributes);
    EXPECT_EQ(std::get<std::string>(attributes.at("microgrid_pattern")), "90,45,135,0");
    EXPECT_EQ(MicrogridPattern::from_attributes(attributes).angles_deg(),
              MicrogridPattern::sony_imx250mzr().angles_deg());
    attributes.erase("microgrid_pattern_deg");
    EXPECT_THROW(MicrogridPattern::from_attributes(attributes), Error);
    attributes["microgrid_pattern_deg"] = std::vector<double>{0.0, 45.0, 90.0};
    EXPECT_THROW(MicrogridPattern::from_attributes(attributes), Error);
}

}  // namespace
}  // namespace tirpol::calibration
