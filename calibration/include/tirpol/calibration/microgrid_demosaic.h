#pragma once
/// \file microgrid_demosaic.h
/// Demosaicing of a microgrid (division-of-focal-plane) frame into one full plane per analyzer
/// angle, float in and float out (no 8/16-bit round trip). Every pixel of a microgrid sees one
/// analyzer angle; the other three are estimated from neighbours that look at a slightly different
/// place, which is the instantaneous-field-of-view (IFOV) error: false polarization at edges and on
/// gradients.

#include <array>
#include <span>
#include <string_view>
#include <vector>

#include "tirpol/calibration/microgrid_pattern.h"

namespace tirpol::calibration {

enum class DemosaicMethod {
    /// One Stokes sample per 2×2 cell (half resolution in x and y): no interpolation, the IFOV
    /// error
    /// of the cell itself (its four pixels see four places).
    SuperPixel,
    /// Each missing angle is the mean of its nearest 2 (horizontal or vertical) or 4 (diagonal)
    /// samples: B. M. Ratliff, C. F. LaCasse & J. S. Tyo, "Interpolation strategies for reducing
    /// IFOV
    /// artifacts in microgrid polarimeter imagery", Opt. Express 17(11), 9112–9125 (2009).
    Bilinear,
    /// Edge-directed second-order Newton-polynomial interpolation in the polarization-difference
    /// domain, after N. Li, Y. Zhao, Q. Pan & S. G. Kong, "Demosaicking DoFP images using Newton's
    /// polynomial interpolation and polarization difference model", Opt. Express 27(2), 1376–1391
    /// (2019). docs/microgrid.md gives the formulas and where this simplifies the paper.
    Newton,
};

/// "super-pixel", "bilinear", "newton": the name recorded in outputs and accepted by the CLI.
std::string_view demosaic_method_name(DemosaicMethod method);
/// The publication a method follows ("" for super-pixel), recorded in outputs.
std::string_view demosaic_method_reference(DemosaicMethod method);
/// Parses a method name; throws tirpol::Error naming `context`, the text and the accepted names.
DemosaicMethod parse_demosaic_method(std::string_view text, std::string_view context = "--method");

/// Four planes, one per analyzer angle of the pattern, in the pattern's cell order.
struct DemosaicedFrame {
    int width = 0;   ///< of the planes: the mosaic's width, or half of it for super-pixel
    int height = 0;  ///< of the planes
    DemosaicMethod method = DemosaicMethod::Bilinear;
    std::array<double, 4> angles_deg{};        ///< nominal analyzer angle of each plane
    std::array<std::vector<float>, 4> planes;  ///< row-major, width × height each
};

/// Demosaics a row-major `width`×`height` mosaic whose pixel (x, y) sits behind the analyzer
/// `pattern.angle_at_pixel_deg(x, y)`. Borders are handled by mirroring about the edge pixel (which
/// keeps each pixel's analyzer). Throws tirpol::Error naming `source` for odd or < 4 sizes, a size
/// that does not match the data, or a non-finite value (naming the first such pixel).
DemosaicedFrame demosaic_microgrid(std::span<const float> mosaic, int width, int height,
                                   const MicrogridPattern& pattern, DemosaicMethod method,
                                   std::string_view source = "microgrid frame");

}  // namespace tirpol::calibration
