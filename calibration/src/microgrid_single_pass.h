#pragma once
// Demosaicing and Stokes reduction of a microgrid frame in one pass over its rows, for one analyzer
// model for every pixel: S = M·I + c is then the same 3×4 matrix for every pixel (W⁺ with each
// column divided by its analyzer's transmission, c = −Σ W⁺ b/t), so no four-plane intermediate
// image and no per-pixel solve are needed. Equal to demosaic_microgrid + reduce_stokes to float
// rounding (tests/calibration/microgrid_single_pass_test.cpp).

#include <array>
#include <cstdint>
#include <span>

#include "tirpol/calibration/analyzer.h"
#include "tirpol/calibration/microgrid_stokes.h"
#include "tirpol/calibration/stokes_reduction.h"
#include "tirpol/core/image.h"

namespace tirpol::calibration::detail {

/// S_r = Σ_c matrix[r][c]·I_c + offset[r], c the pattern's cell positions (0,0), (0,1), (1,0),
/// (1,1).
struct CellStokesMatrix {
    std::array<std::array<float, 4>, 3> matrix{};
    std::array<float, 3> offset{};
};

/// The matrix of `model` (4 positions whose nominal angles are the pattern's) for `pattern`.
CellStokesMatrix cell_stokes_matrix(const AnalyzerModel& model, const MicrogridPattern& pattern);

/// Channels S0 S1 S2 DoLP AoP and reduce_stokes's attributes (without σ, wire grid or L_SLAR), at
/// the mosaic's size or half of it for super-pixel. The frame must have passed
/// check_microgrid_frame / check_microgrid_size.
Image reduce_microgrid_single_pass(std::span<const float> mosaic, int width, int height,
                                   const MicrogridPattern& pattern, const AnalyzerModel& model,
                                   DemosaicMethod method, const ReductionOptions& options);
/// The same for a 16-bit frame, read as it is (no float copy of the frame for super-pixel and
/// bilinear).
Image reduce_microgrid_single_pass(std::span<const std::uint16_t> mosaic, int width, int height,
                                   const MicrogridPattern& pattern, const AnalyzerModel& model,
                                   DemosaicMethod method, const ReductionOptions& options);

}  // namespace tirpol::calibration::detail
