#pragma once
/// \file microgrid_stokes.h
/// Stokes images from one microgrid (division-of-focal-plane) frame: demosaic, then the Stokes
/// reduction S = W⁺·I of stokes_reduction.h with the analyzer model of the pattern's four angles.
/// Also the ideal forward model (scene Stokes → mosaic), its inverse for an ideal analyzer.
///
/// Demosaicing of a microgrid (division-of-focal-plane) frame into one full plane per analyzer
/// angle, float in and float out (no 8/16-bit round trip). Every pixel of a microgrid sees one
/// analyzer angle; the other three are estimated from neighbours that look at a slightly different
/// place, which is the instantaneous-field-of-view (IFOV) error: false polarization at edges and on
/// gradients.
///
/// The 2×2 analyzer pattern of a division-of-focal-plane (microgrid) polarimeter: which nominal
/// analyzer angle sits at which position of every 2×2 cell of the focal plane. Position (row, col)
/// of a pixel is (y mod 2, x mod 2), row-major, origin top-left, angles in the camera frame of
/// ARCHITECTURE.md (0° along image rows, counter-clockwise looking at the scene).

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "tirpol/calibration/analyzer.h"
#include "tirpol/calibration/stokes_reduction.h"
#include "tirpol/core/image.h"

namespace tirpol::calibration {

/// A validated microgrid pattern: four distinct nominal angles in [0°, 180°) whose ideal analyzer
/// rows ½·(1, cos 2θ, sin 2θ) span (S0, S1, S2), i.e. a Stokes-complete set for linear
/// polarization.
class MicrogridPattern {
public:
    /// Angles at cell positions (0,0), (0,1), (1,0), (1,1), degrees. Throws tirpol::Error naming
    /// `context` when an angle is not finite, outside [0°, 180°), repeated (to 0.01°), or the four
    /// do not determine S1 and S2 (condition number of the ideal measurement matrix above 10).
    MicrogridPattern(const std::array<double, 4>& angles_deg,
                     std::string_view context = "microgrid pattern");

    /// The Sony IMX250MZR/MYR layout: (0,0) = 90°, (0,1) = 45°, (1,0) = 135°, (1,1) = 0°.
    static MicrogridPattern sony_imx250mzr();
    /// Parses "90,45,135,0" (the four angles in cell order (0,0), (0,1), (1,0), (1,1)) or the name
    /// "sony" / "imx250mzr". Throws tirpol::Error naming `context` and the text on anything else.
    static MicrogridPattern parse(std::string_view text, std::string_view context = "--pattern");
    /// Reads the pattern that write_to() recorded in an image header; throws tirpol::Error naming
    /// the attribute when it is missing or not four angles.
    static MicrogridPattern from_attributes(const Attributes& attributes);

    /// Nominal angle at cell position (row, col), each 0 or 1.
    double angle_deg(int row, int col) const {
        return m_angles_deg[static_cast<std::size_t>(row * 2 + col)];
    }
    /// Angle of the pixel at image coordinates (x, y).
    double angle_at_pixel_deg(int x, int y) const { return angle_deg(y & 1, x & 1); }
    /// The four angles in cell order (0,0), (0,1), (1,0), (1,1).
    const std::array<double, 4>& angles_deg() const { return m_angles_deg; }
    /// Cell index (row·2 + col) of the position holding `angle_deg`; throws tirpol::Error if
    /// absent.
    int cell_of(double angle_deg) const;
    /// "90,45,135,0".
    std::string text() const;
    /// Records the pattern as attributes `microgrid_pattern` (text) and `microgrid_pattern_deg`
    /// (the four angles in cell order).
    void write_to(Attributes& attributes) const;

private:
    std::array<double, 4> m_angles_deg;
};

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
