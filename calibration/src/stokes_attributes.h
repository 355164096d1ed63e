#pragma once
// The header attributes every Stokes reduction writes (units, convention, analyzer angles, DRM,
// counts): one definition, shared by reduce_stokes and the single-pass microgrid reduction, so the
// two outputs cannot drift apart.

#include <Eigen/Core>

#include "tirpol/calibration/analyzer.h"
#include "tirpol/calibration/stokes_reduction.h"
#include "tirpol/core/image.h"

namespace tirpol::calibration::detail {

/// Writes units (per channel), the Stokes convention, `analyzer_angles_deg`, `drm` (row-major),
/// `unrealizable_pixels` and `wire_grid_corrected`.
void write_stokes_attributes(Image& out, const AnalyzerModel& model, const Eigen::Matrix3Xd& drm,
                             const ReductionOptions& options, int unrealizable,
                             bool wire_grid_corrected);

}  // namespace tirpol::calibration::detail
