#include "label_layout.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace tirpol::report::detail {

bool Box::overlaps(const Box& o, double gap) const {
    return x0 - gap < o.x1 && o.x0 - gap < x1 && y0 - gap < o.y1 && o.y0 - gap < y1;
}

double label_width_em(std::string_view utf8) {
    std::size_t code_points = 0;
    for (const char c : utf8)
        if ((static_cast<unsigned char>(c) & 0xC0u) != 0x80u) ++code_points;
    return kLabelEmPerCodePoint * static_cast<double>(code_points);
}

namespace {

Box at(double x0, double y0, double w, double h) { return {x0, y0, x0 + w, y0 + h}; }

// The point of `b` nearest to (x, y).
std::pair<double, double> nearest_point(const Box& b, double x, double y) {
    return {std::clamp(x, b.x0, b.x1), std::clamp(y, b.y0, b.y1)};
}

double distance(const Box& a, const Box& b) {
    const double dx = std::max({0.0, a.x0 - b.x1, b.x0 - a.x1});
    const double dy = std::max({0.0, a.y0 - b.y1, b.y0 - a.y1});
    return std::hypot(dx, dy);
}

struct Attempt {
    const std::vector<Box>& targets;
    double width, height, gap;
    std::vector<Box> placed;

    bool inside_picture(const Box& b) const {
        return b.x0 >= gap && b.y0 >= gap && b.x1 <= width - gap && b.y1 <= height - gap;
    }
    bool free(const Box& b) const {
        return inside_picture(b) && std::none_of(placed.begin(), placed.end(),
                                                 [&](const Box& p) { return b.overlaps(p, gap); });
    }
    // Covers another region's box (its outline or inside): allowed only as a last resort.
    bool covers_other(const Box& b, std::size_t self) const {
        for (std::size_t i = 0; i < targets.size(); ++i)
            if (i != self && b.overlaps(targets[i])) return true;
        return false;
    }

    std::optional<Box> place(std::size_t i, double w, double h) {
        const Box& t = targets[i];
        const double s = gap;
        // On the region (top-left, centred), then beside it: above, below, right, left.
        const std::vector<Box> attached = {
            at(t.x0 + s, t.y0 + s, w, h),
            at(0.5 * (t.x0 + t.x1 - w), 0.5 * (t.y0 + t.y1 - h), w, h),
            at(t.x0, t.y0 - h - s, w, h),
            at(t.x1 - w, t.y0 - h - s, w, h),
            at(t.x0, t.y1 + s, w, h),
            at(t.x1 - w, t.y1 + s, w, h),
            at(t.x1 + s, t.y0, w, h),
            at(t.x0 - w - s, t.y0, w, h),
            at(t.x1 + s, t.y1 - h, w, h),
            at(t.x0 - w - s, t.y1 - h, w, h),
        };
        for (const bool allow_cover : {false, true}) {
            for (const auto& b : attached)
                if (free(b) && (allow_cover || !covers_other(b, i))) return b;
            // Anywhere on a grid, nearest to the region first.
            std::optional<Box> best;
            double best_distance = std::numeric_limits<double>::infinity();
            const double step = std::max(2.0, 0.25 * h);
            for (double y = gap; y + h <= height - gap; y += step)
                for (double x = gap; x + w <= width - gap; x += step) {
                    const Box b = at(x, y, w, h);
                    const double d = distance(b, t);
                    if (d >= best_distance || !free(b) || (!allow_cover && covers_other(b, i)))
                        continue;
                    best = b;
                    best_distance = d;
                }
            if (best) return best;
        }
        return std::nullopt;
    }
};

}  // namespace

LabelLayout place_labels(const std::vector<double>& width_em, const std::vector<Box>& targets,
                         double width, double height, double font_px, double gap) {
    constexpr double kSmallestFontPx = 7.0;
    LabelLayout layout;
    for (double font = font_px;; font = std::max(kSmallestFontPx, 0.85 * font)) {
        Attempt attempt{targets, width, height, gap, {}};
        std::vector<PlacedLabel> labels;
        bool fits = true;
        for (std::size_t i = 0; i < targets.size() && fits; ++i) {
            const auto box =
                attempt.place(i, std::max(1.0, width_em[i] * font), kLabelHeightEm * font);
            if (!box) {
                fits = false;
                break;
            }
            attempt.placed.push_back(*box);
            PlacedLabel label;
            label.box = *box;
            label.leader = distance(*box, targets[i]) > 1.5 * gap;
            if (label.leader) {
                const Box& t = targets[i];
                const auto [tx, ty] =
                    nearest_point(t, 0.5 * (box->x0 + box->x1), 0.5 * (box->y0 + box->y1));
                const auto [bx, by] = nearest_point(*box, tx, ty);
                label = {label.box, true, bx, by, tx, ty};
            }
            labels.push_back(label);
        }
        // The smallest font places what it can: the rest go where they ask, overlapping.
        if (fits || font <= kSmallestFontPx) {
            for (std::size_t i = labels.size(); i < targets.size(); ++i)
                labels.push_back(
                    {at(targets[i].x0, targets[i].y0, width_em[i] * font, kLabelHeightEm * font)});
            layout.font_px = font;
            layout.labels = std::move(labels);
            return layout;
        }
    }
}

}  // namespace tirpol::report::detail
