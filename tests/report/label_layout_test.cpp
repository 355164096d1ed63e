// Placement of region names on the overview: never two overlapping, never outside the picture,
// on the region when there is room, with a leader line when a label had to move away, and a
// smaller font only when the picture is too crowded.

#include "label_layout.h"

#include <gtest/gtest.h>

using namespace tirpol::report::detail;

namespace {

void expect_disjoint_and_inside(const LabelLayout& layout, double width, double height) {
    for (std::size_t i = 0; i < layout.labels.size(); ++i) {
        const Box& a = layout.labels[i].box;
        EXPECT_GE(a.x0, 0.0) << i;
        EXPECT_GE(a.y0, 0.0) << i;
        EXPECT_LE(a.x1, width) << i;
        EXPECT_LE(a.y1, height) << i;
        for (std::size_t j = i + 1; j < layout.labels.size(); ++j)
            EXPECT_FALSE(a.overlaps(layout.labels[j].box)) << i << " and " << j;
    }
}

}  // namespace

TEST(ReportLabelLayout, WidthCountsCodePointsNotBytes) {
    EXPECT_DOUBLE_EQ(label_width_em("abc"), 3 * kLabelEmPerCodePoint);
    EXPECT_DOUBLE_EQ(label_width_em("Süd ❄"), 5 * kLabelEmPerCodePoint);  // 8 bytes
}

TEST(ReportLabelLayout, ALabelWithRoomSitsOnItsRegionWithoutLeader) {
    const auto layout =
        place_labels({label_width_em("panel")}, {{100, 100, 300, 200}}, 580, 440, 15.0, 3.0);
    ASSERT_EQ(layout.labels.size(), 1u);
    EXPECT_DOUBLE_EQ(layout.font_px, 15.0);
    const Box& b = layout.labels[0].box;
    EXPECT_FALSE(layout.labels[0].leader);
    EXPECT_GE(b.x0, 100.0);
    EXPECT_GE(b.y0, 100.0);
    EXPECT_LE(b.x1, 300.0);
    EXPECT_LE(b.y1, 200.0);
}

TEST(ReportLabelLayout, ALabelAtTheRightEdgeIsNotClipped) {
    // The twin's "flat_black_paint" panel near the right edge was drawn past the picture.
    const auto layout = place_labels({label_width_em("flat_black_paint")}, {{520, 60, 570, 110}},
                                     580, 440, 15.0, 3.0);
    expect_disjoint_and_inside(layout, 580, 440);
    EXPECT_FALSE(layout.labels[0].leader);  // beside its region, above or below
}

TEST(ReportLabelLayout, NineCrowdedPanelsWithLongNamesNeverOverlap) {
    // A 3 × 3 grid of 60 px panels 10 px apart, like the twin's, with names of 16–23 characters.
    const std::vector<std::string> names = {
        "flat_black_paint",   "glossy_black_paint",      "rough_aluminium",
        "white_paint_panel",  "specular_gold_reflector", "oxidised_copper",
        "painted_steel_blue", "anodised_aluminium",      "rough_concrete_slab"};
    std::vector<double> em;
    std::vector<Box> targets;
    for (std::size_t i = 0; i < names.size(); ++i) {
        em.push_back(label_width_em(names[i]));
        const double x = 200.0 + 70.0 * static_cast<double>(i % 3);
        const double y = 120.0 + 70.0 * static_cast<double>(i / 3);
        targets.push_back({x, y, x + 60.0, y + 60.0});
    }
    const auto layout = place_labels(em, targets, 580, 440, 15.0, 3.0);
    ASSERT_EQ(layout.labels.size(), names.size());
    EXPECT_DOUBLE_EQ(layout.font_px, 15.0);
    expect_disjoint_and_inside(layout, 580, 440);
    std::size_t leaders = 0;
    for (const auto& label : layout.labels) {
        if (!label.leader) continue;
        ++leaders;
        // The leader joins the label's box to its region's box.
        EXPECT_TRUE(label.leader_x0 >= label.box.x0 - 1e-9 &&
                    label.leader_x0 <= label.box.x1 + 1e-9);
        EXPECT_TRUE(label.leader_y0 >= label.box.y0 - 1e-9 &&
                    label.leader_y0 <= label.box.y1 + 1e-9);
    }
    EXPECT_GT(leaders, 0u) << "nine 200 px names cannot all sit on 60 px panels";
}

TEST(ReportLabelLayout, ATooSmallPictureShrinksTheFont) {
    // Four 20-character labels in a 200 × 60 picture: at 15 px each is 180 × 19.5 px, only two fit.
    const std::vector<double> em(4, label_width_em("a_twenty_char_name__"));
    const std::vector<Box> targets = {
        {10, 10, 30, 30}, {40, 10, 60, 30}, {70, 10, 90, 30}, {100, 10, 120, 30}};
    const auto layout = place_labels(em, targets, 200, 60, 15.0, 2.0);
    EXPECT_LT(layout.font_px, 15.0);
    expect_disjoint_and_inside(layout, 200, 60);
}
