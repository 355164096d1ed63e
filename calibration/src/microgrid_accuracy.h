#pragma once
/// \file microgrid_accuracy.h
/// How far a Stokes image reduced from a microgrid frame is from the scene's known full-resolution
/// Stokes: the measure by which demosaicing methods are compared (tests, bench, docs/microgrid.md).

#include <cstddef>
#include <span>

#include "tirpol/core/image.h"

namespace tirpol::calibration {

/// Errors of an estimate against the truth over the compared pixels (same units as the Stokes).
struct StokesErrors {
    double s0_rms = 0.0;
    double s1_rms = 0.0;
    double s2_rms = 0.0;
    double dolp_rms =
        0.0;  ///< RMS of DoLP_est − DoLP_true (1); on an unpolarized region, the false DoLP
    double dolp_max = 0.0;   ///< max |DoLP_est − DoLP_true| (1)
    std::size_t pixels = 0;  ///< how many pixels were compared
};

/// Compares `estimate` (channels S0 S1 S2 DoLP, e.g. from reduce_microgrid) with the truth planes
/// (width × height) at full resolution; an estimate of half the size (super-pixel) is compared by
/// giving each of its values to the 2×2 pixels of its cell. Pixels within `border_px` of the frame
/// edge are left out, and so are those where `mask` (empty = all) is 0. Throws tirpol::Error for
/// sizes that do not match or when no pixel is left to compare.
StokesErrors compare_to_truth(const Image& estimate, std::span<const float> s0,
                              std::span<const float> s1, std::span<const float> s2, int width,
                              int height, int border_px = 0,
                              std::span<const unsigned char> mask = {});

}  // namespace tirpol::calibration
