#pragma once
/// \file microgrid_stokes.h
/// Stokes images from one microgrid (division-of-focal-plane) frame: demosaic, then the Stokes
/// reduction S = W⁺·I of stokes_reduction.h with the analyzer model of the pattern's four angles.
/// Also the ideal forward model (scene Stokes → mosaic), its inverse for an ideal analyzer.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "tirpol/calibration/analyzer.h"
#include "tirpol/calibration/microgrid_demosaic.h"
#include "tirpol/calibration/microgrid_pattern.h"
#include "tirpol/calibration/stokes_reduction.h"
#include "tirpol/core/image.h"

namespace tirpol::calibration {

/// What a microgrid camera with ideal analyzers (d = 1, t = 1, no background) records of a scene
/// whose Stokes planes (camera frame, width × height, row-major) are given: pixel (x, y) holds
/// ½·(S0 + S1 cos 2θ + S2 sin 2θ), θ = pattern.angle_at_pixel_deg(x, y) (the row a_k of
/// analyzer.h). Throws tirpol::Error if a plane does not hold width × height values.
std::vector<float> microgrid_from_stokes(std::span<const float> s0, std::span<const float> s1,
                                         std::span<const float> s2, int width, int height,
                                         const MicrogridPattern& pattern);

struct MicrogridReductionOptions {
    DemosaicMethod method = DemosaicMethod::Newton;
    /// The analyzer model of the four micro-polarizers (one model for every pixel), e.g. from
    /// estimate_analyzer(); its nominal angles must be the pattern's. Empty: ideal analyzers at the
    /// pattern's angles.
    AnalyzerModel analyzer;
    ReductionOptions reduction;
    std::string source = "microgrid frame";  ///< named in errors
    /// Demosaic and reduce in one pass over the rows with the model's fixed 3×4 matrix (no
    /// four-plane intermediate image; equal to the two-step path to float rounding, AoP by a
    /// polynomial atan). False, or `reduction.include_slar`: demosaic_microgrid, then the general
    /// reduce_stokes (double precision per pixel).
    bool single_pass = true;
};

/// Demosaics `mosaic` and reduces it to channels S0 S1 S2 DoLP AoP (reduce_stokes), at the mosaic's
/// size or, for super-pixel, half of it. Attributes: those of reduce_stokes, the pattern
/// (MicrogridPattern::write_to), `demosaic_method` and `demosaic_reference`. Throws tirpol::Error
/// for a bad frame (demosaic_microgrid) or an analyzer model whose angles are not the pattern's.
Image reduce_microgrid(std::span<const float> mosaic, int width, int height,
                       const MicrogridPattern& pattern,
                       const MicrogridReductionOptions& options = {});
/// The same for a 16-bit frame (a camera's raw counts), read without a float copy of the frame on
/// the single pass of super-pixel and bilinear.
Image reduce_microgrid(std::span<const std::uint16_t> mosaic, int width, int height,
                       const MicrogridPattern& pattern,
                       const MicrogridReductionOptions& options = {});

}  // namespace tirpol::calibration
