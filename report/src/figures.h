#pragma once
// Image figures of the comparison report, drawn with OpenCV (colour maps and colorbars from core's
// quicklook); line-art plots and the region names are SVG (svg_plot.h). Private to the report
// module. Text drawn by OpenCV is ASCII only (colour-bar numbers and units).

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "label_layout.h"
#include "tirpol/core/quicklook.h"
#include "tirpol/report/regions.h"

namespace tirpol::report::detail {

/// A plane of display data (already reduced to display size), width × height, row-major.
struct Plane {
    std::vector<float> data;
    int width = 0, height = 0;
};

/// Longest side of the images drawn in the report; larger inputs are averaged down (INTER_AREA).
inline constexpr int kDisplayMaxSide = 400;
/// `data` (width × height) reduced to fit kDisplayMaxSide (unchanged if it already fits).
Plane display_plane(const std::vector<float>& data, int width, int height);

/// BGR colour of region `index` (Tableau 10 palette).
std::vector<int> region_colour(std::size_t index);
/// The same as a CSS "#rrggbb".
std::string region_colour_css(std::size_t index);

/// Writes the quicklooks of `planes` (same height) to `parts` and their horizontal composition to
/// `panel`.
void write_panel(const std::filesystem::path& panel,
                 const std::vector<std::filesystem::path>& parts, const std::vector<Plane>& planes,
                 const std::vector<QuicklookOptions>& options);

/// Measured S0 in grey with the region polygons outlined, as PNG bytes; the names are not drawn
/// (Hershey fonts are ASCII only) but returned with their boxes, placed so that none overlaps
/// another or leaves the picture (label_layout.h), for the SVG overlay (svg_plot.h).
struct RegionOverview {
    std::string png;            ///< encoded PNG
    int width = 0, height = 0;  ///< of the PNG, pixels
    double font_px = 15.0;      ///< font size of every label
    struct Label {
        std::string name;
        PlacedLabel placed;      ///< text box (PNG pixels) and leader line, if any
        std::string colour_css;  ///< the region's outline colour
    };
    std::vector<Label> labels;
};
RegionOverview region_overview(const std::vector<float>& s0, int width, int height,
                               const std::vector<Region>& regions);

/// One set of scatter points: (measured, simulated) pairs of one region.
struct ScatterSeries {
    std::string name;
    std::vector<float> measured, simulated;
};
/// [p_lo, p_hi] percentiles of `values` (a small interval around a constant).
std::pair<double, double> percentile_range(std::vector<float> values, double lo_p, double hi_p);

}  // namespace tirpol::report::detail
