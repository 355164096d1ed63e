#pragma once
/// \file datasheet_analyzer.h
/// The analyzer model from a polarizer's datasheet, for a polarimetric calibration without
/// known-source records: the extinction ratio and the transmission-axis offsets of the mount.

#include <string>
#include <vector>

#include "tirpol/calibration/analyzer.h"

namespace tirpol::calibration {

struct DatasheetAnalyzer {
    double extinction_ratio = 0.0;  ///< t_max/t_min > 1 (e.g. 100–300 for an LWIR wire grid)
    std::vector<double>
        axis_offsets_deg;  ///< axis − nominal: none (0°), one for all, or one per angle
};

/// The model at `angles_deg` (ascending): d = (ER − 1)/(ER + 1), θ_k = nominal_k + offset_k, t = 1
/// + 1/ER. Throws tirpol::Error for ER ≤ 1 or not finite, offsets of another count than 0, 1 or the
/// number of angles (naming both), or an offset of 45° or more.
AnalyzerModel datasheet_analyzer_model(const std::vector<double>& angles_deg,
                                       const DatasheetAnalyzer& datasheet);

/// "datasheet (extinction ratio 150, axis offsets +1.50°)", for the calibration's analyzer method.
std::string describe(const DatasheetAnalyzer& datasheet);

}  // namespace tirpol::calibration
