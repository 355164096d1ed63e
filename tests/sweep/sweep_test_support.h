#pragma once
// Small, fast sweep files over the shipped scenes for the sweep tests.

#include <string>

#include "test_support.h"

namespace tirpol::sweep::test {

/// A sweep file in `dir` over the shipped night ball-on-snow scene at a tiny resolution and few
/// samples, followed by `body` (axes, regions, …).
inline std::filesystem::path write_small_sweep(const tirpol::test::TempDir& dir,
                                               const std::string& body,
                                               const std::string& name = "sweep.yaml") {
    const auto path = dir / name;
    tirpol::test::write_text(
        path, "scene: " +
                  (tirpol::test::source_dir() / "config/scenes/ball_on_snow_night.yaml").string() +
                  "\nset:\n  camera.resolution: [32, 24]\n  sampling.spp: 4\n" + body);
    return path;
}

}  // namespace tirpol::sweep::test
