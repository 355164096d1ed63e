#pragma once
// A synthetic Stokes image from a per-pixel function, for tests that plant a scene.

#include <array>
#include <functional>

#include "tirpol/core/image.h"

namespace tirpol::test {

/// An image with channels S0, S1, S2 whose pixel (x, y) is `stokes(x, y)`; pixels are visited row
/// by row, so a noise generator called inside `stokes` is drawn in raster order.
inline Image stokes_image(int width, int height,
                          const std::function<std::array<double, 3>(int x, int y)>& stokes) {
    Image image(width, height);
    auto& s0 = image.add_channel("S0");
    auto& s1 = image.add_channel("S1");
    auto& s2 = image.add_channel("S2");
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t i = image.index(x, y);
            const std::array<double, 3> s = stokes(x, y);
            s0[i] = static_cast<float>(s[0]);
            s1[i] = static_cast<float>(s[1]);
            s2[i] = static_cast<float>(s[2]);
        }
    return image;
}

}  // namespace tirpol::test
