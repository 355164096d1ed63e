#pragma once
// Placement of the region names on the region overview: no two labels overlap, none leaves the
// picture, and a label that cannot sit on or beside its region is joined to it by a leader line.
// Greedy: each label, in region order, takes the first free spot among those on or beside its
// region, else the free spot nearest to it on a grid over the picture; when none is free the
// whole layout is retried with a smaller font.

#include <string_view>
#include <vector>

namespace tirpol::report::detail {

/// Axis-aligned box in picture pixels: left, top, right, bottom.
struct Box {
    double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
    double width() const { return x1 - x0; }
    double height() const { return y1 - y0; }
    /// True when the boxes share interior area once each is grown by `gap` / 2 on every side.
    bool overlaps(const Box& other, double gap = 0.0) const;
};

/// The label text's advance width in em: code points × kLabelEmPerCodePoint. The page draws the
/// text with exactly this length (SVG textLength), so the layout's boxes are those the browser
/// shows.
inline constexpr double kLabelEmPerCodePoint = 0.6;
/// Height of a label's box in em: covers the font's ascent and descent (≈ 1.17 em for DejaVu
/// Sans) around a centred baseline.
inline constexpr double kLabelHeightEm = 1.3;
double label_width_em(std::string_view utf8);

struct PlacedLabel {
    Box box;              ///< where the text goes (its centre line is the box's vertical centre)
    bool leader = false;  ///< the box neither touches nor lies on its region: draw a leader line
    double leader_x0 = 0.0, leader_y0 = 0.0;  ///< from the box's edge …
    double leader_x1 = 0.0, leader_y1 = 0.0;  ///< … to the nearest point of the region's box
};

struct LabelLayout {
    double font_px = 0.0;             ///< the font size all labels were placed with
    std::vector<PlacedLabel> labels;  ///< one per request, in request order
};

/// Places one label of `width_em[i]` em per region bounding box `targets[i]` inside a picture of
/// `width` × `height` px, starting at `font_px` and shrinking by 15 % (to no less than 7 px) until
/// every label fits with `gap` px between labels and from the picture's edge. `width_em` and
/// `targets` have the same length.
LabelLayout place_labels(const std::vector<double>& width_em, const std::vector<Box>& targets,
                         double width, double height, double font_px, double gap);

}  // namespace tirpol::report::detail
