// The heated checkerboard target as a scene object, and the calibration views of it.

#include "tirpol/simulation/heated_board.h"

#include <fmt/format.h>

#include <cmath>

#include "tirpol/core/exr_io.h"
#include "tirpol/core/image.h"

namespace tirpol::simulation {

std::string HeatedBoard::target() const {
    switch (pattern) {
        case Pattern::Circles:
            return fmt::format("circles:{}x{}:{}", squares_x, squares_y, square_m);
        case Pattern::AsymmetricCircles:
            return fmt::format("acircles:{}x{}:{}", squares_x / 2, squares_y, square_m);
        case Pattern::Checkerboard:
            break;
    }
    return fmt::format("checkerboard:{}x{}:{}", squares_x - 1, squares_y - 1, square_m);
}

namespace {
/// Square (i, j) of the board (1-based: the cold border is row and column 0) is hot on a
/// checkerboard.
bool hot_square(int i, int j) { return (i + j) % 2 == 0; }
}  // namespace

Vec3 HeatedBoard::inner_corner(int c, int r) const {
    const double x = -0.5 * size_x() + (2 + c) * square_m, y = -0.5 * size_y() + (2 + r) * square_m;
    return centre + (standing ? Vec3(x, 0.0, y) : Vec3(x, y, 0.0));
}

std::vector<Vec3> HeatedBoard::features() const {
    std::vector<Vec3> out;
    auto at = [&](double x_m, double y_m) {
        out.push_back(centre + (standing ? Vec3(x_m, 0.0, y_m) : Vec3(x_m, y_m, 0.0)));
    };
    for (int j = 1; j <= squares_y; ++j)
        for (int i = 1; i <= squares_x; ++i) {
            const double x = -0.5 * size_x() + (i + 0.5) * square_m,
                         y = -0.5 * size_y() + (j + 0.5) * square_m;
            if (pattern == Pattern::Checkerboard) {
                if (i < squares_x && j < squares_y) at(x + 0.5 * square_m, y + 0.5 * square_m);
            } else if (pattern == Pattern::Circles || hot_square(i, j)) {
                at(x, y);
            }
        }
    return out;
}

std::string HeatedBoard::write(const std::filesystem::path& dir) const {
    const int w = (squares_x + 2) * texels_per_square, h = (squares_y + 2) * texels_per_square;
    constexpr int kSub = 4;  // sub-texels for the discs' edge coverage, symmetric about each centre
    const double radius_texels = 0.5 * disc_diameter_m / square_m * texels_per_square;
    Image map(w, h);
    auto& t = map.add_channel("temperature_k");
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const int i = x / texels_per_square, j = y / texels_per_square;
            const bool on_board = i >= 1 && j >= 1 && i <= squares_x && j <= squares_y;
            double hot = 0.0;
            if (pattern == Pattern::Checkerboard) {
                hot = on_board && hot_square(i, j) ? 1.0 : 0.0;
            } else if (on_board && (pattern == Pattern::Circles || hot_square(i, j))) {
                const double cx = (i + 0.5) * texels_per_square, cy = (j + 0.5) * texels_per_square;
                for (int sy = 0; sy < kSub; ++sy)
                    for (int sx = 0; sx < kSub; ++sx)
                        hot += std::hypot(x + (sx + 0.5) / kSub - cx, y + (sy + 0.5) / kSub - cy) <
                               radius_texels;
                hot /= kSub * kSub;
            }
            t[map.index(x, y)] = static_cast<float>(cold_k + hot * (hot_k - cold_k));
        }
    write_exr(dir / "board_temperature.exr", map);
    return fmt::format(
        "  - {{name: board, geometry: {{type: plane, size: [{}, {}]}}, transform: {{rotate_deg: "
        "[{}, 0, 0], translate: "
        "[{}, {}, {}]}}, material: flat_black_paint, temperature: {{texture: "
        "board_temperature.exr, channel: "
        "temperature_k}}}}\n",
        size_x(), size_y(), standing ? 90 : 0, centre.x(), centre.y(), centre.z());
}

std::string board_scene(const std::string& board_object, const std::filesystem::path& materials_dir,
                        const std::string& lens, const Vec3& position, const Vec3& look_at,
                        const Vec3& up, int spp) {
    // Board frames stand in for a camera's S0 frames, which have no per-pixel error bars: one
    // replicate keeps all of a pixel's samples in one net, so the squares' edges are placed by the
    // sequence's sub-pixel strata (8 one-point replicates at 8 spp gave 0.21 px RMS reprojection
    // error).
    return fmt::format(
        "band: {{lo_um: 8, hi_um: 14}}\nsampling: {{spp: {}, replicates: 1, max_bounces: 0, seed: "
        "1}}\nmaterials_dir: {}\n"
        "camera: {{model: {}, position: [{}, {}, {}], look_at: [{}, {}, {}], up: [{}, {}, {}]}}\n"
        "sky: {{type: uniform, temperature: 230}}\nobjects:\n{}",
        spp, materials_dir.string(), lens, position.x(), position.y(), position.z(), look_at.x(),
        look_at.y(), look_at.z(), up.x(), up.y(), up.z(), board_object);
}

std::vector<BoardView> board_calibration_views(int count, double fx_px, int width_px,
                                               double max_tilt_deg, double roll_spread_deg) {
    // Distances and shifts scale with fx / width, so the board covers the same part of any frame.
    const double scale = (fx_px / width_px) / (762.0 / 640.0);
    std::vector<BoardView> views;
    for (int i = 0; i < count; ++i) {
        const double tilt = deg_to_rad(20.0 + (max_tilt_deg - 20.0) * (i % 5) / 4.0),
                     azimuth = 2.0 * kPi * i / count;
        const double distance = scale * (1.1 + 0.04 * (i % 4));
        const Vec3 position = distance * Vec3(std::sin(tilt) * std::cos(azimuth),
                                              std::sin(tilt) * std::sin(azimuth), std::cos(tilt));
        const Vec3 look_at =
            scale * Vec3(0.05 * std::cos(3.0 * azimuth), 0.035 * std::sin(2.0 * azimuth), 0.0);
        const double roll = deg_to_rad(90.0 + roll_spread_deg * std::sin(1.7 * i));
        views.push_back(
            {position, look_at, Vec3(std::cos(azimuth + roll), std::sin(azimuth + roll), 0.0)});
    }
    return views;
}

}  // namespace tirpol::simulation
