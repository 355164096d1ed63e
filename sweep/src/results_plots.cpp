// plots/<axis>_<quantity>.png (sweep_results.h).

#include <fmt/format.h>

#include <array>
#include <cctype>
#include <cmath>

#include "results.h"
#include "tirpol/core/quicklook.h"

namespace tirpol::sweep::detail {

namespace {

// Matplotlib's "tab10" colours, one per region or contrast.
constexpr std::array<std::array<std::uint8_t, 3>, 10> kColours = {{{31, 119, 180},
                                                                   {255, 127, 14},
                                                                   {44, 160, 44},
                                                                   {214, 39, 40},
                                                                   {148, 103, 189},
                                                                   {140, 86, 75},
                                                                   {227, 119, 194},
                                                                   {127, 127, 127},
                                                                   {188, 189, 34},
                                                                   {23, 190, 207}}};

std::string file_name(const std::string& parameter) {
    std::string out;
    for (char c : parameter) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    return out;
}

}  // namespace

std::vector<std::filesystem::path> write_axis_plots(const SweepSpec& spec,
                                                    const std::filesystem::path& out_dir,
                                                    const std::vector<PointRecord>& points) {
    std::vector<std::filesystem::path> written;
    for (std::size_t a = 0; a < spec.axes.size(); ++a) {
        const auto line = points_along(spec, points, a);
        if (spec.axes[a].values.size() < 2 || line.size() < 2) continue;
        // Quantities with a Monte-Carlo error: temperature_k is plotted too, it drives the
        // time-of-day trend.
        for (std::size_t q = 0; q < std::size(kQuantityNames); ++q) {
            std::vector<PlotSeries> series;
            const auto add = [&](const std::string& name, bool dashed, const auto& values_of) {
                PlotSeries s{name, {}, {}, kColours[series.size() % kColours.size()], true, dashed};
                bool finite = false;
                for (std::size_t i : line) {
                    if (!points[i].statistics) continue;
                    s.x.push_back(spec.axes[a].coordinates[points[i].point.value_index[a]]);
                    s.y.push_back(quantity(values_of(*points[i].statistics), q).mean);
                    finite = finite || std::isfinite(s.y.back());
                }
                if (finite) series.push_back(std::move(s));
            };
            for (std::size_t r = 0; r < spec.regions.size(); ++r)
                add(
                    spec.regions[r].name, false, [r](const PointStatistics& s) -> const auto& {
                        return s.regions[r].values;
                    });
            for (std::size_t c = 0; c < spec.contrasts.size(); ++c)
                add(
                    spec.contrasts[c].name, true, [c](const PointStatistics& s) -> const auto& {
                        return s.contrasts[c].values;
                    });
            if (series.empty()) continue;
            LinePlotOptions options;
            options.title = fmt::format("{} vs {}", kQuantityNames[q], spec.axes[a].parameter);
            options.x_label = spec.axes[a].coordinate_label;
            options.y_label = std::string(kQuantityNames[q]) + (q < 3 ? " [W/(m2 sr)]" : "");
            written.push_back(
                out_dir / "plots" /
                fmt::format("{}_{}.png", file_name(spec.axes[a].parameter), kQuantityNames[q]));
            std::filesystem::create_directories(written.back().parent_path());
            write_line_plot(written.back(), series, options);
        }
    }
    return written;
}

}  // namespace tirpol::sweep::detail
