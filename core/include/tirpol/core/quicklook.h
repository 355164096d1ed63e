#pragma once
/// \file quicklook.h
/// PNG quicklooks of one channel with a colour map chosen for the quantity and a labelled colorbar.
///
/// Simple 2-D line plots as PNG (axes, 1-2-5 ticks, labels, legend), for curves people look at:
/// emissivity vs angle (paper Fig. 1), measured vs modelled, calibration curves. Drawn with OpenCV.

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace tirpol {

enum class Colormap {
    Sequential,  ///< intensities (S0, radiance, temperature): perceptually uniform "inferno"
    Diverging,   ///< signed quantities centred on zero (S1, S2, differences): cool-warm
    Cyclic,      ///< angles (AoP, 0–180°): "twilight"
};

struct QuicklookOptions {
    Colormap colormap = Colormap::Sequential;
    std::optional<double> vmin,
        vmax;           ///< default: robust range (1st–99th percentile; symmetric for Diverging)
    std::string title;  ///< e.g. "S1"
    std::string units;  ///< e.g. "W/(m²·sr)"
    int scale = 0;      ///< integer upscaling of small images; 0 = automatic
    /// Text chunks written into the PNG (keyword, text), in order: a tEXt chunk when the text is
    /// ASCII, else an iTXt chunk (UTF-8). Keywords: 1–79 printable ASCII characters, no leading,
    /// trailing or double spaces (PNG specification §11.3.4.2).
    std::vector<std::pair<std::string, std::string>> text;
};

/// Range that `write_quicklook` would use for `data` given `options`.
std::pair<double, double> quicklook_range(const std::vector<float>& data,
                                          const QuicklookOptions& options);

/// Writes a PNG of `data` (width × height, row-major) with a colorbar annotated with the range and
/// units. NaN pixels are drawn grey. Atomic write.
void write_quicklook(const std::filesystem::path& path, const std::vector<float>& data, int width,
                     int height, const QuicklookOptions& options);

/// The default colour map for a channel name (S1/S2/S3/differences diverging, AoP cyclic, else
/// sequential).
Colormap default_colormap(const std::string& channel_name);

/// The options every Stokes quicklook the project writes uses for a channel: its colour map and
/// title, a unit on the colour bar (S0–S3 `radiance_units`, DoLP "fraction", AoP "deg",
/// temperature_k "K") and fixed ends where the quantity has them: DoLP from 0 (its minimum by
/// definition, so a colour means the same DoLP in every image; the top stays robust), AoP 0–180.
QuicklookOptions channel_quicklook_options(const std::string& channel_name,
                                           const std::string& radiance_units = "W/(m²·sr)");

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
