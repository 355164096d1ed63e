#pragma once
/// \file line_plot.h
/// Simple 2-D line plots as PNG (axes, 1-2-5 ticks, labels, legend), for curves people look at:
/// emissivity vs angle (paper Fig. 1), measured vs modelled, calibration curves. Drawn with OpenCV.

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tirpol {

struct PlotSeries {
    std::string label;         ///< legend text (ASCII; OpenCV's Hershey fonts have no Greek)
    std::vector<double> x, y;  ///< same length; non-finite points break the line
    std::array<std::uint8_t, 3> rgb = {31, 119, 180};
    bool markers = false;  ///< draw a small circle at every point
    bool dashed = false;
};

struct LinePlotOptions {
    std::string title, x_label, y_label;
    std::optional<double> x_min, x_max, y_min,
        y_max;                       ///< default: the data range, padded by 5% for y
    int width = 900, height = 600;   ///< pixels
    bool zero_line = true;           ///< draw y = 0 when it is inside the range
    double legend_y_fraction = 0.0;  ///< legend position: 0 = top of the axes, 1 = bottom
};

/// Writes the plot as a PNG (atomically). Throws tirpol::Error for no series, mismatched x/y
/// lengths, an empty data range, or an unwritable path.
void write_line_plot(const std::filesystem::path& path, const std::vector<PlotSeries>& series,
                     const LinePlotOptions& options);

/// "Nice" tick positions (steps of 1, 2 or 5 × 10^k) covering [lo, hi] with about `target` ticks.
std::vector<double> nice_ticks(double lo, double hi, int target = 6);

}  // namespace tirpol
