#pragma once
// report.html: one self-contained page (PNG figures as base64 data URIs, inline CSS, no script, no
// external resource) that reads on a laptop screen and prints on A4. Private to the report module.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "tirpol/report/comparison_report.h"

namespace tirpol::report::detail {

struct Figure {
    std::string section;         ///< "regions", "images", "z", "scatter", "histograms"
    std::filesystem::path file;  ///< the PNG, or the .svg copy of `svg`
    std::string caption;         ///< HTML-escaped by the writer
    std::string svg;             ///< inline SVG plot; empty for a PNG figure
};

/// `text` made valid UTF-8 and escaped for HTML/SVG text and attribute values (& < > ").
std::string escape_markup(std::string_view text);

/// RFC 4648 base64 of `bytes` (standard alphabet, padded).
std::string base64_encode(std::string_view bytes);

/// The whole page for `result`, with `figures` embedded in their sections, in order (PNGs as data
/// URIs, plots as inline SVG).
std::string render_html(const CompareResult& result, const std::string& measured_name,
                        const std::string& simulated_name, const std::vector<Figure>& figures);

}  // namespace tirpol::report::detail
