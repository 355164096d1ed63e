#pragma once
/// \file microgrid_pattern.h
/// The 2×2 analyzer pattern of a division-of-focal-plane (microgrid) polarimeter: which nominal
/// analyzer angle sits at which position of every 2×2 cell of the focal plane. Position (row, col)
/// of a pixel is (y mod 2, x mod 2), row-major, origin top-left, angles in the camera frame of
/// ARCHITECTURE.md (0° along image rows, counter-clockwise looking at the scene).

#include <array>
#include <string>
#include <string_view>

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

}  // namespace tirpol::calibration
