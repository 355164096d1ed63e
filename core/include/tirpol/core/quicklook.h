#pragma once
/// \file quicklook.h
/// PNG quicklooks of one channel with a colour map chosen for the quantity and a labelled colorbar.

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

}  // namespace tirpol
