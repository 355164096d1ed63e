#pragma once
/// \file microgrid_session.h
/// A capture session of a microgrid (division-of-focal-plane) camera → Stokes image. The session's
/// manifest records the camera's 2×2 analyzer pattern (`camera.microgrid_pattern_deg`, session
/// schema v5); every polarizer record holds whole mosaics, so the records are averaged (weighted by
/// their frame counts) and the mean mosaic is reduced: demosaiced and reduced with ideal analyzers
/// at the pattern's angles (reduce_microgrid), or, with a per-pixel calibration, per 2×2
/// super-pixel with each pixel's own analysis vector (reduce_microgrid_per_pixel).

#include <filesystem>
#include <optional>

#include "tirpol/calibration/microgrid_pixel_calibration.h"
#include "tirpol/calibration/microgrid_stokes.h"
#include "tirpol/core/image.h"

namespace tirpol::calibration {

struct MicrogridSessionOptions {
    DemosaicMethod method = DemosaicMethod::Newton;  ///< without a per-pixel calibration
    /// Each pixel's analysis vector (Powell & Gruev); its size must be the camera's. When set, the
    /// output is per super-pixel (half size) and `method` is not used.
    std::optional<MicrogridPixelCalibration> pixel_calibration;
};

/// True when the session at `dir` was recorded by a microgrid camera (its manifest records a
/// pattern). Throws tirpol::Error as read_session does for a damaged session.
bool is_microgrid_session(const std::filesystem::path& dir);

/// Reduces the session at `dir`. Output channels S0 S1 S2 DoLP AoP in counts (with a per-pixel
/// calibration: in its Stokes units, and S0_std … AoP_std from the records' temporal σ and the
/// calibration's parameter uncertainties, MicrogridPixelReducer::reduce), attributes those of
/// the reduction plus `session` (the directory), `records_averaged`, `frames_averaged` and the
/// pattern. Throws tirpol::Error naming the session when it records no microgrid pattern (a
/// rotating-polarizer session), has no polarizer record, or its pattern does not determine S1 and
/// S2; naming the calibration when its size is not the camera's.
Image reduce_microgrid_session(const std::filesystem::path& dir,
                               const MicrogridSessionOptions& options = {});

}  // namespace tirpol::calibration
