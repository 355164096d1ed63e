#pragma once
// Views and regions of the render-fit tests (render_fit_test.cpp) and of the experiments that
// repeat them (experiments/): the scene's camera moved to look at a point, and a region split
// into quadrants.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "tirpol/fitting/render_fit.h"
#include "tirpol/simulation/pinhole_camera.h"
#include "tirpol/simulation/scene.h"

namespace tirpol::test {

/// Index of the scene object called `name` (a test failure and 0 when there is none).
inline std::size_t object_named(const simulation::Scene& scene, const std::string& name) {
    for (std::size_t i = 0; i < scene.objects.size(); ++i)
        if (scene.objects[i].name == name) return i;
    ADD_FAILURE() << "no object " << name;
    return 0;
}

/// `base`'s lens at `position`, looking at `look_at` with +z up.
inline simulation::PinholeCamera camera_at(const simulation::PinholeCamera& base,
                                           const Vec3& position, const Vec3& look_at) {
    return simulation::PinholeCamera(
        base.width(), base.height(), base.intrinsics(), position,
        simulation::PinholeCamera::look_at(position, look_at, Vec3(0.0, 0.0, 1.0)));
}

/// Splits a region into four quadrants about its centroid (different view angles on a sphere).
inline std::vector<fitting::RenderFitRegion> quadrants(const fitting::RenderFitRegion& r,
                                                       int width) {
    double cx = 0.0, cy = 0.0;
    for (std::size_t i : r.pixels)
        cx += static_cast<double>(i % width), cy += static_cast<double>(i / width);
    cx /= static_cast<double>(r.pixels.size()), cy /= static_cast<double>(r.pixels.size());
    std::vector<fitting::RenderFitRegion> out{{r.name + "_top", {}},
                                              {r.name + "_right", {}},
                                              {r.name + "_bottom", {}},
                                              {r.name + "_left", {}}};
    for (std::size_t i : r.pixels) {
        const double dx = static_cast<double>(i % width) - cx,
                     dy = static_cast<double>(i / width) - cy;
        const int q = std::abs(dy) > std::abs(dx) ? (dy < 0 ? 0 : 2) : (dx > 0 ? 1 : 3);
        out[static_cast<std::size_t>(q)].pixels.push_back(i);
    }
    return out;
}

}  // namespace tirpol::test
