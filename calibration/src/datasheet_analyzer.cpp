#include <fmt/format.h>

#include <cmath>

#include "tirpol/calibration/analyzer.h"
#include "tirpol/core/error.h"

namespace tirpol::calibration {

AnalyzerModel datasheet_analyzer_model(const std::vector<double>& angles_deg,
                                       const DatasheetAnalyzer& datasheet) {
    if (!(datasheet.extinction_ratio > 1.0) || !std::isfinite(datasheet.extinction_ratio))
        fail("datasheet extinction ratio {}; expected a finite t_max/t_min above 1",
             datasheet.extinction_ratio);
    const std::size_t n_offsets = datasheet.axis_offsets_deg.size();
    if (n_offsets > 1 && n_offsets != angles_deg.size())
        fail("{} axis offsets for {} analyzer angles; expected none, one for all, or one per angle",
             n_offsets, angles_deg.size());
    AnalyzerModel model;
    for (std::size_t k = 0; k < angles_deg.size(); ++k) {
        const double offset =
            n_offsets == 0 ? 0.0 : datasheet.axis_offsets_deg[n_offsets == 1 ? 0 : k];
        if (!(std::abs(offset) < 45.0))
            fail(
                "axis offset {}° at {:g}°; expected |offset| < 45° (the mount's error, not another "
                "angle)",
                offset, angles_deg[k]);
        model.positions.push_back(
            AnalyzerModel::non_ideal({angles_deg[k]}, datasheet.extinction_ratio, offset)
                .positions.front());
    }
    return model;
}

std::string describe(const DatasheetAnalyzer& datasheet) {
    std::string offsets;
    for (double o : datasheet.axis_offsets_deg)
        offsets += fmt::format("{}{:+.2f}°", offsets.empty() ? "" : ", ", o);
    return fmt::format("datasheet (extinction ratio {:g}, axis offsets {})",
                       datasheet.extinction_ratio, offsets.empty() ? "0°" : offsets);
}

}  // namespace tirpol::calibration
