#include <fmt/format.h>

#include <regex>

#include "tirpol/calibration/geometric_calibration.h"
#include "tirpol/core/error.h"

namespace tirpol::calibration {

CalibrationTarget CalibrationTarget::parse(const std::string& text) {
    static const std::regex pattern(
        R"(^(checkerboard|circles|acircles):(\d+)x(\d+):([0-9.eE+-]+)$)");
    std::smatch m;
    if (!std::regex_match(text, m, pattern))
        fail(
            "target '{}': expected checkerboard:COLSxROWS:SQUARE_M (inner corners, e.g. "
            "checkerboard:9x6:0.04), "
            "circles:COLSxROWS:PITCH_M or acircles:COLSxROWS:HALF_PITCH_M",
            text);
    CalibrationTarget t;
    t.kind = m[1] == "checkerboard" ? Kind::Checkerboard
             : m[1] == "circles"    ? Kind::Circles
                                    : Kind::AsymmetricCircles;
    t.columns = std::stoi(m[2]);
    t.rows = std::stoi(m[3]);
    try {
        t.spacing_m = std::stod(m[4]);
    } catch (const std::exception&) {
        fail("target '{}': spacing '{}' is not a number in metres", text, m[4].str());
    }
    if (t.columns < 3 || t.rows < 3)
        fail("target '{}': need at least 3x3 features, got {}x{}", text, t.columns, t.rows);
    if (t.kind == Kind::Checkerboard && t.columns == t.rows)
        fail(
            "target '{}': a square checkerboard ({}x{} inner corners) has no unique orientation; "
            "use one with an "
            "odd and an even count, e.g. 9x6",
            text, t.columns, t.rows);
    if (t.kind == Kind::AsymmetricCircles && t.rows % 2 == 0)
        fail(
            "target '{}': an asymmetric circle grid needs an odd number of rows (e.g. "
            "acircles:4x11); with {} rows "
            "OpenCV's detector returns the circles in an order that does not match the grid's "
            "layout",
            text, t.rows);
    if (!(t.spacing_m > 0.0 && t.spacing_m < 100.0))
        fail("target '{}': spacing must be in (0, 100) m", text);
    return t;
}

std::string CalibrationTarget::to_string() const {
    const char* name = kind == Kind::Checkerboard ? "checkerboard"
                       : kind == Kind::Circles    ? "circles"
                                                  : "acircles";
    return fmt::format("{}:{}x{}:{}", name, columns, rows, spacing_m);
}

std::vector<Vec3> CalibrationTarget::object_points() const {
    std::vector<Vec3> points;
    points.reserve(point_count());
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < columns; ++c) {
            // OpenCV's asymmetric grid: odd rows are shifted by one spacing along the row.
            const double x =
                kind == Kind::AsymmetricCircles ? (2 * c + r % 2) * spacing_m : c * spacing_m;
            points.emplace_back(x, r * spacing_m, 0.0);
        }
    return points;
}

}  // namespace tirpol::calibration
