// The heated checkerboard target as a scene object, and the calibration views of it.

#include "tirpol/simulation/heated_board.h"

#include <fmt/format.h>

#include <cmath>

#include "tirpol/core/exr_io.h"
#include "tirpol/core/image.h"

namespace tirpol::simulation {

std::string HeatedBoard::target() const {
    return fmt::format("checkerboard:{}x{}:{}", squares_x - 1, squares_y - 1, square_m);
}

Vec3 HeatedBoard::inner_corner(int c, int r) const {
    const double x = -0.5 * size_x() + (2 + c) * square_m, y = -0.5 * size_y() + (2 + r) * square_m;
    return centre + (standing ? Vec3(x, 0.0, y) : Vec3(x, y, 0.0));
}

std::string HeatedBoard::write(const std::filesystem::path& dir) const {
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
        "  - {{name: board, geometry: {{type: plane, size: [{}, {}]}}, transform: {{rotate_deg: [{}, 0, 0], translate: "
        "[{}, {}, {}]}}, material: flat_black_paint, temperature: {{texture: board_temperature.exr, channel: "
        "temperature_k}}}}\n",
        size_x(), size_y(), standing ? 90 : 0, centre.x(), centre.y(), centre.z());
}

std::string board_scene(const std::string& board_object, const std::filesystem::path& materials_dir,
                        const std::string& lens, const Vec3& position, const Vec3& look_at, const Vec3& up, int spp) {
    return fmt::format(
        "band: {{lo_um: 8, hi_um: 14}}\nsampling: {{spp: {}, max_bounces: 0, seed: 1}}\nmaterials_dir: {}\n"
        "camera: {{model: {}, position: [{}, {}, {}], look_at: [{}, {}, {}], up: [{}, {}, {}]}}\n"
        "sky: {{type: uniform, temperature: 230}}\nobjects:\n{}",
        spp, materials_dir.string(), lens, position.x(), position.y(), position.z(), look_at.x(), look_at.y(),
        look_at.z(), up.x(), up.y(), up.z(), board_object);
}

std::vector<BoardView> board_calibration_views(int count, double fx_px, int width_px, double max_tilt_deg,
                                              double roll_spread_deg) {
    // Distances and shifts scale with fx / width, so the board covers the same part of any frame.
    const double scale = (fx_px / width_px) / (762.0 / 640.0);
    std::vector<BoardView> views;
    for (int i = 0; i < count; ++i) {
        const double tilt = deg_to_rad(20.0 + (max_tilt_deg - 20.0) * (i % 5) / 4.0), azimuth = 2.0 * kPi * i / count;
        const double distance = scale * (1.1 + 0.04 * (i % 4));
        const Vec3 position =
            distance * Vec3(std::sin(tilt) * std::cos(azimuth), std::sin(tilt) * std::sin(azimuth), std::cos(tilt));
        const Vec3 look_at = scale * Vec3(0.05 * std::cos(3.0 * azimuth), 0.035 * std::sin(2.0 * azimuth), 0.0);
        const double roll = deg_to_rad(90.0 + roll_spread_deg * std::sin(1.7 * i));
        views.push_back({position, look_at, Vec3(std::cos(azimuth + roll), std::sin(azimuth + roll), 0.0)});
    }
    return views;
}

}  // namespace tirpol::simulation
