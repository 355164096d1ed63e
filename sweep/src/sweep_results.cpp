#include "sweep_results.h"

#include "results.h"

namespace tirpol::sweep {

std::vector<std::size_t> points_along(const SweepSpec& spec, const std::vector<PointRecord>& points,
                                      std::size_t axis) {
    std::vector<std::size_t> line;
    for (std::size_t i = 0; i < points.size(); ++i) {
        bool on_line = true;
        for (std::size_t a = 0; a < spec.axes.size() && spec.combine == Combine::Grid; ++a)
            on_line = on_line && (a == axis || points[i].point.value_index[a] == 0);
        if (on_line) line.push_back(i);
    }
    return line;
}

std::vector<std::filesystem::path> write_results(const SweepSpec& spec,
                                                 const std::filesystem::path& out_dir,
                                                 const std::vector<PointRecord>& points) {
    std::vector<std::filesystem::path> written = detail::write_tables(spec, out_dir, points);
    for (auto* part : {&detail::write_axis_plots, &detail::write_image_summaries}) {
        const auto more = (*part)(spec, out_dir, points);
        written.insert(written.end(), more.begin(), more.end());
    }
    return written;
}

}  // namespace tirpol::sweep
