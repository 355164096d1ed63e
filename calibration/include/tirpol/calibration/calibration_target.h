#pragma once
/// \file calibration_target.h
/// The planar targets of geometric calibration (docs/camera-geometry.md): a checkerboard (aluminium
/// tape on black paint, or a heated board) or a grid of circles (heated discs, holes in a cold
/// plate). Feature points lie in the target's plane z = 0 of its own frame, x along a row, y down
/// the columns, in OpenCV's detection order (row by row).

#include <string>
#include <vector>

#include "tirpol/core/camera_model.h"

namespace tirpol::calibration {

struct CalibrationTarget {
    enum class Kind { Checkerboard, Circles, AsymmetricCircles };
    Kind kind = Kind::Checkerboard;
    int columns = 0;  ///< inner corners (checkerboard) or circles along a row
    int rows = 0;     ///< inner corners or circles down a column
    double spacing_m =
        0.0;  ///< square side; circle pitch; for the asymmetric grid half the pitch along a row

    /// Parses `checkerboard:COLSxROWS:SQUARE_M`, `circles:COLSxROWS:PITCH_M` or
    /// `acircles:COLSxROWS:HALF_PITCH_M` (OpenCV's asymmetric grid). COLSxROWS count inner corners
    /// of a checkerboard (a board of 10×7 squares is 9x6). Throws naming what was expected.
    static CalibrationTarget parse(const std::string& text);
    std::string to_string() const;

    std::size_t point_count() const {
        return static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows);
    }
    /// Feature positions in the target frame, metres, in detection order.
    std::vector<Vec3> object_points() const;
};

}  // namespace tirpol::calibration
