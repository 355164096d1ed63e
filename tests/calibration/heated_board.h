#pragma once
// The heated checkerboard of the geometric-calibration tests (simulation/heated_board.h) in a scene
// whose materials come from the source tree.

#include <string>

#include "test_support.h"
#include "tirpol/simulation/heated_board.h"

namespace tirpol::test {

using simulation::HeatedBoard;

/// A scene of `board_object` seen by the camera model file `lens` (simulation::board_scene).
inline std::string board_scene(const std::string& board_object, const std::string& lens,
                               const Vec3& position, const Vec3& look_at, const Vec3& up, int spp) {
    return simulation::board_scene(board_object, source_dir() / "config" / "materials", lens,
                                   position, look_at, up, spp);
}

}  // namespace tirpol::test
