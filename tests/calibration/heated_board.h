#pragma once
// A heated checkerboard rendered by the simulation (the renderer is the source of truth for
// geometric calibration tests): a plane whose temperature is an EXR texture of hot and cold squares,
// as a board of aluminium-tape squares on a heated plate appears to an LWIR camera.

#include <fmt/format.h>

#include <filesystem>
#include <string>

#include "test_support.h"
#include "tirpol/core/camera_model.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/image.h"
#include "tirpol/simulation/renderer.h"
#include "tirpol/simulation/scene.h"

namespace tirpol::test {

struct HeatedBoard {
    int squares_x = 10, squares_y = 7;  ///< squares; inner corners are one fewer each way
    double square_m = 0.06;
    int texels_per_square = 24;
    double hot_k = 308.0, cold_k = 293.0;
    /// The plane spans the squares plus a one-square cold border; it lies in the world xy plane,
    /// centred at `centre`, with texture u along +x and v along +y (docs/scene-format.md). Standing,
    /// it is turned 90° about x: v along +z, facing −y.
    Vec3 centre = Vec3::Zero();
    bool standing = false;

    double size_x() const { return (squares_x + 2) * square_m; }
    double size_y() const { return (squares_y + 2) * square_m; }
    std::string target() const { return fmt::format("checkerboard:{}x{}:{}", squares_x - 1, squares_y - 1, square_m); }
    /// World position of inner corner (c, r), c along x, r along y.
    Vec3 inner_corner(int c, int r) const {
        const double x = -0.5 * size_x() + (2 + c) * square_m, y = -0.5 * size_y() + (2 + r) * square_m;
        return centre + (standing ? Vec3(x, 0.0, y) : Vec3(x, y, 0.0));
    }

    /// Writes the temperature texture and returns the scene's `objects:` entry for the board.
    std::string write(const std::filesystem::path& dir) const {
        const int w = (squares_x + 2) * texels_per_square, h = (squares_y + 2) * texels_per_square;
        Image map(w, h);
        auto& t = map.add_channel("temperature_k");
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const int i = x / texels_per_square, j = y / texels_per_square;
                const bool on_board = i >= 1 && j >= 1 && i <= squares_x && j <= squares_y;
                t[map.index(x, y)] = static_cast<float>(on_board && (i + j) % 2 == 0 ? hot_k : cold_k);
            }
        write_exr(dir / "board_temperature.exr", map);
        return fmt::format(
            "  - {{name: board, geometry: {{type: plane, size: [{}, {}]}}, transform: {{rotate_deg: [{}, 0, 0], translate: [{}, {}, {}]}}, "
            "material: flat_black_paint, temperature: {{texture: board_temperature.exr, channel: temperature_k}}}}\n",
            size_x(), size_y(), standing ? 90 : 0, centre.x(), centre.y(), centre.z());
    }
};

/// A scene of `board` seen by the camera model file `lens` from `position` looking at `look_at` with
/// image-up `up`; emission only (max_bounces 0), a cold uniform sky.
inline std::string board_scene(const std::string& board_object, const std::string& lens, const Vec3& position,
                               const Vec3& look_at, const Vec3& up, int spp) {
    return fmt::format(
        "band: {{lo_um: 8, hi_um: 14}}\nsampling: {{spp: {}, max_bounces: 0, seed: 1}}\nmaterials_dir: {}\n"
        "camera: {{model: {}, position: [{}, {}, {}], look_at: [{}, {}, {}], up: [{}, {}, {}]}}\n"
        "sky: {{type: uniform, temperature: 230}}\nobjects:\n{}",
        spp, (source_dir() / "config" / "materials").string(), lens, position.x(), position.y(), position.z(), look_at.x(),
        look_at.y(), look_at.z(), up.x(), up.y(), up.z(), board_object);
}

}  // namespace tirpol::test
