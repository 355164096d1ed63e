#pragma once
// The checks every microgrid frame passes before a per-pixel loop touches it (the loops never
// throw): whole 2×2 cells, the right number of values and, for float frames, finite ones.

#include <cstddef>
#include <span>
#include <string_view>

namespace tirpol::calibration::detail {

/// Throws tirpol::Error naming `source` unless the frame is width × height values with an even
/// width and height of at least 4.
void check_microgrid_size(std::size_t values, int width, int height, std::string_view source);

/// check_microgrid_size, and every value finite (the first non-finite pixel is named).
void check_microgrid_frame(std::span<const float> mosaic, int width, int height,
                           std::string_view source);

}  // namespace tirpol::calibration::detail
