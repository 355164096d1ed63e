#pragma once
/// \file heated_board.h
/// A heated checkerboard as a scene object, and a standard set of views of it: the renderer is the
/// source of truth of geometric calibration (the calibration tests and the digital twin render what
/// a field user films). The board is a plane whose temperature is an EXR texture of hot and cold
/// squares, as a board of aluminium-tape squares on a heated plate appears to an LWIR camera.

#include <filesystem>
#include <string>
#include <vector>

#include "tirpol/core/geometry.h"

namespace tirpol::simulation {

struct HeatedBoard {
    /// Checkerboard: hot and cold squares. Circles: a hot disc centred in every square of the board
    /// (OpenCV's symmetric grid, squares_x × squares_y circles, pitch square_m). AsymmetricCircles:
    /// a hot disc in the squares that are hot on the checkerboard (OpenCV's asymmetric grid,
    /// squares_x / 2 × squares_y circles, half pitch square_m; squares_x even). Cold around the
    /// discs, as a heated plate behind a cold mask with holes.
    enum class Pattern { Checkerboard, Circles, AsymmetricCircles };
    Pattern pattern = Pattern::Checkerboard;
    int squares_x = 10, squares_y = 7;  ///< squares; inner corners are one fewer each way
    double square_m = 0.06;
    double disc_diameter_m = 0.03;  ///< circle patterns
    int texels_per_square = 24;
    double hot_k = 308.0, cold_k = 293.0;
    /// The plane spans the squares plus a one-square cold border; it lies in the world xy plane,
    /// centred at `centre`, with texture u along +x and v along +y (docs/scene-format.md).
    /// Standing, it is turned 90° about x: v along +z, facing −y.
    Vec3 centre = Vec3::Zero();
    bool standing = false;

    double size_x() const { return (squares_x + 2) * square_m; }
    double size_y() const { return (squares_y + 2) * square_m; }
    /// The `--target` of `tirpol calibrate geometric` for this board (inner corners or circles).
    std::string target() const;
    /// World position of inner corner (c, r), c along x, r along y.
    Vec3 inner_corner(int c, int r) const;
    /// World positions of the target's feature points: inner corners, or disc centres.
    std::vector<Vec3> features() const;
    /// Writes the temperature texture `board_temperature.exr` into `dir` and returns the scene's
    /// `objects:` entry for the board (material flat_black_paint).
    std::string write(const std::filesystem::path& dir) const;
};

/// A scene file's text: `board_object` seen by the camera model file `lens` (relative to the scene
/// file) from `position` looking at `look_at` with image-up `up`; emission only (max_bounces 0), a
/// cold uniform sky, materials from `materials_dir`.
std::string board_scene(const std::string& board_object, const std::filesystem::path& materials_dir,
                        const std::string& lens, const Vec3& position, const Vec3& look_at,
                        const Vec3& up, int spp);

struct BoardView {
    Vec3 position, look_at, up;
};

/// `count` views of the default HeatedBoard lying at the origin, for a camera of focal length
/// `fx_px` and `width_px` pixels: tilted 20° to `max_tilt_deg` toward the camera from all around,
/// at the distance where the board fills the frame as it does 1.1–1.3 m from a 640-pixel camera
/// with fx = 762 px, shifted so the frame's corners (where the distortion is largest) are covered,
/// rolled about the optical axis by up to ±`roll_spread_deg` — varied tilts make the focal length
/// observable (Zhang, IEEE TPAMI 22(11), 2000), varied rolls separate the principal point from the
/// tilts.
std::vector<BoardView> board_calibration_views(int count, double fx_px, int width_px,
                                               double max_tilt_deg = 40.0,
                                               double roll_spread_deg = 25.0);

}  // namespace tirpol::simulation
